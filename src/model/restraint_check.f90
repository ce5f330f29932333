!> Static check that every body is held against rigid-body motion.
!!
!! Nodes are grouped into connected bodies (through elements and any extra
!! links such as contact pairs or ties).  For each body the restrained
!! components give constraint rows on the rigid-body motion
!! (u0, v0, theta): an x restraint at (x, y) gives [1, 0, -y], a y restraint
!! [0, 1, x].  The body is held when these rows have rank 3 (plane problems).
!! In axisymmetry the only rigid-body motion is an axial translation, so one
!! axial (z) restraint per body suffices.  A body that fails is reported with
!! the free motions named, before any matrix is assembled.
module restraint_check
   use kinds, only: dp
   use model, only: model_t, NTYPE_AXISYMMETRIC
   implicit none
   private
   public :: find_bodies, unrestrained_bodies

contains

   !> Label every node with the index of its connected body (0 for unused nodes).
   subroutine find_bodies(m, links, body, nbody)
      type(model_t), intent(in) :: m
      integer, intent(in) :: links(:, :)   !! (2, nlink) extra node-node connections
      integer, intent(out) :: body(:)      !! (npoin) body index of each node
      integer, intent(out) :: nbody
      integer, allocatable :: parent(:)
      integer :: ie, k, a, b, ip, r
      logical, allocatable :: used(:)

      allocate (parent(m%npoin), used(m%npoin))
      parent = [(ip, ip=1, m%npoin)]
      used = .false.
      do ie = 1, m%nelem
         a = m%lnods(1, ie)
         if (a < 1 .or. a > m%npoin) cycle
         used(a) = .true.
         do k = 2, m%nnode_e(ie)
            b = m%lnods(k, ie)
            if (b < 1 .or. b > m%npoin) cycle
            used(b) = .true.
            call unite(parent, a, b)
         end do
      end do
      do k = 1, size(links, 2)
         a = links(1, k)
         b = links(2, k)
         if (a < 1 .or. a > m%npoin .or. b < 1 .or. b > m%npoin) cycle
         used(a) = .true.
         used(b) = .true.
         call unite(parent, a, b)
      end do
      body = 0
      nbody = 0
      do ip = 1, m%npoin
         if (.not. used(ip)) cycle
         r = root(parent, ip)
         if (body(r) == 0) then
            nbody = nbody + 1
            body(r) = nbody
         end if
         body(ip) = body(r)
      end do
   end subroutine find_bodies

   !> For each body, a description of its free rigid-body motions ('' if held).
   subroutine unrestrained_bodies(m, links, nbad, bad_node, what)
      type(model_t), intent(in) :: m
      integer, intent(in) :: links(:, :)
      integer, intent(out) :: nbad                 !! number of bodies not held
      integer, allocatable, intent(out) :: bad_node(:)            !! lowest node of each such body
      character(len=80), allocatable, intent(out) :: what(:)      !! its free motions
      integer, allocatable :: body(:)
      real(dp), allocatable :: gram(:, :, :), xc(:, :), lsize(:)
      integer, allocatable :: cnt(:), lowest(:), nfixz(:)
      integer :: nbody, ib, ip, k, node
      real(dp) :: row(3), x, y, det, tr
      character(len=80) :: s

      allocate (body(m%npoin))
      call find_bodies(m, links, body, nbody)
      allocate (gram(3, 3, nbody), xc(2, nbody), lsize(nbody), cnt(nbody), lowest(nbody), &
                nfixz(nbody))
      gram = 0.0_dp
      xc = 0.0_dp
      cnt = 0
      lowest = huge(1)
      nfixz = 0
      do ip = 1, m%npoin
         ib = body(ip)
         if (ib == 0) cycle
         xc(:, ib) = xc(:, ib) + m%coord(:, ip)
         cnt(ib) = cnt(ib) + 1
         lowest(ib) = min(lowest(ib), ip)
      end do
      do ib = 1, nbody
         xc(:, ib) = xc(:, ib)/max(cnt(ib), 1)
      end do
      lsize = 0.0_dp
      do ip = 1, m%npoin
         ib = body(ip)
         if (ib == 0) cycle
         lsize(ib) = max(lsize(ib), maxval(abs(m%coord(:, ip) - xc(:, ib))))
      end do
      where (lsize <= 0.0_dp) lsize = 1.0_dp
      do k = 1, size(m%fixes)
         node = m%fixes(k)%node
         if (node < 1 .or. node > m%npoin) cycle
         ib = body(node)
         if (ib == 0) cycle
         x = (m%coord(1, node) - xc(1, ib))/lsize(ib)
         y = (m%coord(2, node) - xc(2, ib))/lsize(ib)
         if (m%fixes(k)%fixed(1)) then
            row = [1.0_dp, 0.0_dp, -y]
            gram(:, :, ib) = gram(:, :, ib) + spread(row, 2, 3)*spread(row, 1, 3)
         end if
         if (m%fixes(k)%fixed(2)) then
            row = [0.0_dp, 1.0_dp, x]
            gram(:, :, ib) = gram(:, :, ib) + spread(row, 2, 3)*spread(row, 1, 3)
            nfixz(ib) = nfixz(ib) + 1
         end if
      end do

      allocate (bad_node(nbody), what(nbody))
      nbad = 0
      do ib = 1, nbody
         s = ''
         if (m%ntype == NTYPE_AXISYMMETRIC) then
            if (nfixz(ib) == 0) s = 'axial (z) translation'
         else
            associate (g => gram(:, :, ib))
               tr = g(1, 1) + g(2, 2) + g(3, 3)
               det = g(1, 1)*(g(2, 2)*g(3, 3) - g(2, 3)*g(3, 2)) &
                     - g(1, 2)*(g(2, 1)*g(3, 3) - g(2, 3)*g(3, 1)) &
                     + g(1, 3)*(g(2, 1)*g(3, 2) - g(2, 2)*g(3, 1))
               if (g(1, 1) <= 0.0_dp .and. g(2, 2) <= 0.0_dp) then
                  s = 'translation in x and y, and rotation'
               else if (g(1, 1) <= 0.0_dp) then
                  s = 'translation in x'
               else if (g(2, 2) <= 0.0_dp) then
                  s = 'translation in y'
               else if (det <= 1.0e-10_dp*tr**3) then
                  s = 'rotation'
               end if
            end associate
         end if
         if (len_trim(s) > 0) then
            nbad = nbad + 1
            bad_node(nbad) = lowest(ib)
            what(nbad) = s
         end if
      end do
   end subroutine unrestrained_bodies

   !> Root of the set containing i, halving the path on the way.
   integer function root(parent, i) result(r)
      integer, intent(inout) :: parent(:)
      integer, intent(in) :: i
      r = i
      do while (parent(r) /= r)
         parent(r) = parent(parent(r))
         r = parent(r)
      end do
   end function root

   subroutine unite(parent, a, b)
      integer, intent(inout) :: parent(:)
      integer, intent(in) :: a, b
      integer :: ra, rb
      ra = root(parent, a)
      rb = root(parent, b)
      if (ra /= rb) parent(max(ra, rb)) = min(ra, rb)
   end subroutine unite
end module restraint_check
