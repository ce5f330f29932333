!> Assembly of the contact springs: the equations of every pair's dofs, the
!! spring matrices of the current modes, pair vectors into the free
!! equations, the springs' part of the prescribed displacements, the pairs'
!! couplings for the equation graph, the reference springs of a
!! condensation, and the spring forces at the nodes.
!!
!! A pair's dofs are (u_a, u_2, ..., u_nn), nd = 2 MAX_PAIR_NODES entries of
!! which the first 2 nn are used (see contact_element); `peq(k, j)` is the
!! equation of dof k of pair j, <= 0 for a restrained dof or k > 2 nn.
module contact_assembly
   use kinds, only: dp
   use dof_map, only: dof_map_t
   use contact_types, only: contact_def_t, contact_pair_t, MAX_PAIR_NODES
   use contact_element, only: pair_stiffness
   use contact_algorithm, only: contact_state_t, pair_matrix, pair_force_vector, pair_dofs, &
         start_force_normal
   implicit none
   private
   public :: contact_springs_t, pair_links, pair_values, scatter_free, spring_nodal_forces

   !> The springs of every pair, as the system sees them.
   type :: contact_springs_t
      integer :: npair = 0
      integer :: nd = 2*MAX_PAIR_NODES               !! dofs of the largest pair
      integer, allocatable :: peq(:, :)              !! (nd, npair) equations of the pairs' dofs
      real(dp), allocatable :: kstore(:, :, :)       !! (nd, nd, npair) spring matrices
                                                     !! of the current modes
   contains
      procedure :: init => springs_init
      procedure :: set_matrices => springs_set_matrices
      procedure :: subtract_prescribed => springs_subtract_prescribed
      procedure :: predicted_forces => springs_predicted_forces
      procedure :: start_forces => springs_start_forces
      procedure :: residual_forces => springs_residual_forces
      procedure :: reference_springs => springs_reference
   end type contact_springs_t

contains

   !> Equations of every pair's dofs; spring matrices zero.
   subroutine springs_init(this, map, pairs)
      class(contact_springs_t), intent(inout) :: this
      type(dof_map_t), intent(in) :: map
      type(contact_pair_t), intent(in) :: pairs(:)
      integer :: j, k
      this%npair = size(pairs)
      this%nd = 2*MAX_PAIR_NODES
      if (allocated(this%peq)) deallocate (this%peq)
      if (allocated(this%kstore)) deallocate (this%kstore)
      allocate (this%peq(this%nd, this%npair), this%kstore(this%nd, this%nd, this%npair))
      this%kstore = 0.0_dp
      this%peq = 0
      do j = 1, this%npair
         do k = 1, pairs(j)%nn
            this%peq(2*k - 1:2*k, j) = map%id(:, pairs(j)%nodes(k))
         end do
      end do
   end subroutine springs_init

   !> The spring matrices of the pairs' current modes (eq. 3.31).
   subroutine springs_set_matrices(this, cdef, st)
      class(contact_springs_t), intent(inout) :: this
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer :: j
      do j = 1, this%npair
         call pair_matrix(cdef, st, j, this%kstore(:, :, j))
      end do
   end subroutine springs_set_matrices

   !> b(free) -= K_c u_r: springs attached to prescribed displacements.
   subroutine springs_subtract_prescribed(this, pairs, u, b)
      class(contact_springs_t), intent(in) :: this
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: u(:, :)          !! (2, npoin) displacements, restrained entries used
      real(dp), intent(inout) :: b(:)          !! (neq)
      real(dp), allocatable :: x(:)
      integer :: j, nd
      do j = 1, size(pairs)
         nd = 2*pairs(j)%nn
         if (all(this%peq(1:nd, j) > 0)) cycle
         x = pair_values(u, pairs(j), nd)
         where (this%peq(1:nd, j) > 0) x = 0.0_dp
         call scatter_free(this%peq(1:nd, j), -matmul(this%kstore(1:nd, 1:nd, j), x), b)
      end do
   end subroutine springs_subtract_prescribed

   !> Spring forces at the start of an increment (after begin_increment): rvec
   !! the forces of the pairs' modes, and into rhs the difference from the
   !! committed forces (an ideal pair closed across a gap: the out-of-balance
   !! force of its penalty term); rpred zero.
   subroutine springs_start_forces(this, cdef, st, rvec, rpred, rhs)
      class(contact_springs_t), intent(in) :: this
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      real(dp), intent(out) :: rvec(:, :)      !! (nd, npair)
      real(dp), intent(out) :: rpred(:, :)     !! (nd, npair)
      real(dp), intent(inout) :: rhs(:)        !! (neq)
      integer :: j, k
      do j = 1, this%npair
         call pair_force_vector(cdef, j, st%s(j)%fn, st%s(j)%ft, rpred(:, j))
         call pair_force_vector(cdef, j, start_force_normal(cdef, st, j), st%s(j)%ft, rvec(:, j))
         k = 2*cdef%pairs(j)%nn
         call scatter_free(this%peq(1:k, j), rpred(1:k, j) - rvec(1:k, j), rhs)
      end do
      rpred = 0.0_dp
   end subroutine springs_start_forces

   !> Out-of-balance force of the springs: rvec the internal-force vectors of
   !! the pairs' current forces, rhs (zero off the contact equations) the
   !! forces the solution predicted minus these.
   subroutine springs_residual_forces(this, cdef, st, rpred, rvec, rhs)
      class(contact_springs_t), intent(in) :: this
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: rpred(:, :)      !! (nd, npair) predicted spring forces
      real(dp), intent(inout) :: rvec(:, :)    !! (nd, npair)
      real(dp), intent(out) :: rhs(:)          !! (neq)
      integer :: jp, nv
      do jp = 1, this%npair
         call pair_force_vector(cdef, jp, st%fn(jp), st%ft(jp), rvec(:, jp))
      end do
      rhs = 0.0_dp
      do jp = 1, this%npair
         nv = 2*cdef%pairs(jp)%nn
         call scatter_free(this%peq(1:nv, jp), rpred(1:nv, jp) - rvec(1:nv, jp), rhs)
      end do
   end subroutine springs_residual_forces

   !> Spring forces the last solution predicts: rpred = rvec + K_c dv, pair by pair.
   subroutine springs_predicted_forces(this, pairs, rvec, dv, rpred)
      class(contact_springs_t), intent(in) :: this
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: rvec(:, :)       !! (nd, npair) spring forces
                                               !! the solution started from
      real(dp), intent(in) :: dv(:, :)         !! (2, npoin) the solution
      real(dp), intent(inout) :: rpred(:, :)   !! (nd, npair)
      integer :: j, k
      do j = 1, this%npair
         k = 2*pairs(j)%nn
         rpred(1:k, j) = rvec(1:k, j) + matmul(this%kstore(1:k, 1:k, j), pair_values(dv, &
                                                                                     pairs(j), k))
      end do
   end subroutine springs_predicted_forces

   !> Reference springs K_ref of a condensation: every pair gets a spring of
   !! 0.1 x the smallest diagonal of K_AB on its free equations, in both
   !! directions.  The smallest, because a tied or very stiff side would
   !! otherwise give a reference spring far stiffer than any contact spring,
   !! and K_c - K_ref would lose digits to cancellation.  A rigid body's
   !! reference node has no elements (zero diagonal, skipped): its reference
   !! springs come from the deformable side alone.
   subroutine springs_reference(this, pairs, diag, kref)
      class(contact_springs_t), intent(in) :: this
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: diag(:)                 !! (neq) diagonal of K_AB
      real(dp), allocatable, intent(out) :: kref(:, :, :)   !! (nd, nd, npair)
      real(dp) :: k0
      integer :: j, k, n
      allocate (kref(this%nd, this%nd, this%npair))
      kref = 0.0_dp
      do j = 1, this%npair
         k0 = huge(1.0_dp)
         n = 0
         do k = 1, this%nd
            if (this%peq(k, j) <= 0) cycle
            if (diag(this%peq(k, j)) <= 0.0_dp) cycle
            k0 = min(k0, diag(this%peq(k, j)))
            n = n + 1
         end do
         if (n == 0) k0 = 1.0_dp
         k0 = 0.1_dp*k0
         associate (pr => pairs(j))
            call pair_stiffness(pr%t, pr%n, pr%nn, pr%w, k0, k0, kref(:, :, j))
         end associate
      end do
   end subroutine springs_reference

   !> Node couplings of the pairs for the equation graph: node a with its
   !! master side (node b, the nodes of B under its tributary zone, or a rigid
   !! body's reference node), and those master nodes with each other.
   pure subroutine pair_links(pairs, links)
      type(contact_pair_t), intent(in) :: pairs(:)
      integer, allocatable, intent(out) :: links(:, :)   !! (2, nlink)
      integer :: j, k, ip, nlink
      nlink = 0
      do j = 1, size(pairs)
         nlink = nlink + (pairs(j)%nn*(pairs(j)%nn - 1))/2
      end do
      allocate (links(2, nlink))
      nlink = 0
      do j = 1, size(pairs)
         do k = 2, pairs(j)%nn
            do ip = 1, k - 1
               nlink = nlink + 1
               links(:, nlink) = [pairs(j)%nodes(ip), pairs(j)%nodes(k)]
            end do
         end do
      end do
   end subroutine pair_links

   !> The nd = 2 nn dof values (a_x, a_y, b_x, b_y, ...) of a pair from a nodal field.
   pure function pair_values(v, pr, nd) result(x)
      real(dp), intent(in) :: v(:, :)
      type(contact_pair_t), intent(in) :: pr
      integer, intent(in) :: nd
      real(dp) :: x(nd), y(2*MAX_PAIR_NODES)
      y = pair_dofs(v, pr)
      x = y(1:nd)
   end function pair_values

   !> Add a pair's vector to the free equations (entries with ieq <= 0 are skipped).
   pure subroutine scatter_free(ieq, v, b)
      integer, intent(in) :: ieq(:)
      real(dp), intent(in) :: v(:)
      real(dp), intent(inout) :: b(:)
      integer :: k
      do k = 1, size(ieq)
         if (ieq(k) > 0) b(ieq(k)) = b(ieq(k)) + v(k)
      end do
   end subroutine scatter_free

   !> Internal forces of the springs at the nodes (2, npoin) for the
   !! committed forces: what the springs take from the bodies.
   subroutine spring_nodal_forces(cdef, st, npoin, fsp)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: npoin
      real(dp), allocatable, intent(inout) :: fsp(:, :)
      real(dp) :: r(2*MAX_PAIR_NODES)
      integer :: j, k
      if (.not. allocated(fsp)) allocate (fsp(2, npoin))
      fsp = 0.0_dp
      do j = 1, size(cdef%pairs)
         call pair_force_vector(cdef, j, st%s(j)%fn, st%s(j)%ft, r)
         do k = 1, cdef%pairs(j)%nn
            fsp(:, cdef%pairs(j)%nodes(k)) = fsp(:, cdef%pairs(j)%nodes(k)) + r(2*k - 1:2*k)
         end do
      end do
   end subroutine spring_nodal_forces
end module contact_assembly
