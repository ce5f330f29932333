!> The pretension sections in the analysis (module pretension): their
!! springs in K_AB, their nodal forces, and the force across each section
!! from the elements' internal forces.
!!
!! Section k joins each copy c to its original o through its reference node
!! r along the axis:  g = u_c - u_o - u_r,  energy kp g^2 / 2,  so the spring
!! adds kp [1 -1 -1]^T [1 -1 -1] on (u_c, u_o, u_r).  kp is PENALTY times the
!! larger diagonal of K_AB at the node's and its copy's axial equations: stiff enough
!! that the section opens uniformly to 1/PENALTY of its elements' own
!! compliance, mild enough for the round-off of the factorization (the
!! equations lose about log10(PENALTY) digits: with 1e4 the example joint's
!! skyline and UMFPACK solutions differed by 2.7e-10, with 1e3 by 3.5e-11).  Whatever kp, the
!! reference node's equilibrium makes the springs carry exactly the force on
!! it, so the force across the section is the applied one to the accuracy
!! of the solution.
module pretension_assembly
   use kinds, only: dp
   use errors, only: status_t, STAT_JACOBIAN
   use strings, only: itoa
   use model, only: model_t, MAX_NODE
   use dof_map, only: dof_map_t
   use linear_solver, only: linear_solver_t
   use solid2d, only: element_stiffness, edge_load
   use topology, only: nedges, element_edge_nodes
   use pretension, only: pretension_t
   implicit none
   private
   public :: pretension_run_t, assemble_pretension, pretension_nodal_forces, section_forces, &
         section_shortening, &
             PENALTY

   real(dp), parameter :: PENALTY = 1.0e3_dp

   !> What the analysis keeps of the sections.
   type :: section_springs_t
      real(dp), allocatable :: kp(:)            !! (nodes) spring stiffness
                                                !! at each node [force/length]
      real(dp), allocatable :: w(:)             !! (nodes) the nodes' shares of the section [area]
   end type section_springs_t

   type :: pretension_run_t
      integer :: n = 0                          !! sections
      type(section_springs_t), allocatable :: sections(:)
      ! the lock's memory (pretension_control): the Jacobian of the closures' increments by the
      ! holding forces, and the holding force of every section's last locked increment
      logical :: have_jac = .false.
      real(dp), allocatable :: jac(:, :)        !! (n, n)
      real(dp), allocatable :: x_last(:)        !! (n) [force]
      ! the reference nodes held in the matrix during locked increments (pretension_control): a
      ! spring to ground of stiffness kground on each held reference node's axial equation
      logical, allocatable :: held(:)           !! (n) the spring is in the solver's base
      real(dp), allocatable :: kground(:)       !! (n) its stiffness: the sum of the springs
      ! the holding forces of the locked increments (x and the ground spring's reaction) stay in
      ! the external force on the reference node; an increment that changes the section's force
      ! takes them out again (pretension_control's release_holding): the committed sum, the sum
      ! after the last attempt and the reference node's external force that attempt left
      real(dp), allocatable :: hsum(:)          !! (n) [force] committed
      real(dp), allocatable :: hsum_out(:)      !! (n) [force] after the last attempt
      real(dp), allocatable :: fref_out(:)      !! (n) [force] after the last attempt
      logical :: tried = .false.                !! an attempt has been made
   end type pretension_run_t

contains

   !> Add the sections' springs to the solver's matrix (between
   !! assemble_bodies and store_base); diag and absrow grow with them.
   subroutine assemble_pretension(m, map, solver, pr, diag, absrow)
      type(model_t), intent(in) :: m
      type(dof_map_t), intent(in) :: map
      class(linear_solver_t), intent(inout) :: solver
      type(pretension_run_t), intent(out) :: pr
      real(dp), intent(inout) :: diag(:), absrow(:)   !! (neq) of K_AB
      real(dp) :: ke(3, 3), c(3), ksum
      real(dp), allocatable :: share(:)
      integer :: k, i, ieq(3), ax
      pr%n = 0
      if (allocated(m%pretensions)) pr%n = size(m%pretensions)
      allocate (pr%sections(pr%n), pr%jac(pr%n, pr%n), pr%x_last(pr%n))
      allocate (pr%held(pr%n), pr%kground(pr%n))
      allocate (pr%hsum(pr%n), pr%hsum_out(pr%n), pr%fref_out(pr%n))
      pr%hsum = 0.0_dp
      pr%hsum_out = 0.0_dp
      pr%fref_out = 0.0_dp
      pr%jac = 0.0_dp
      pr%x_last = 0.0_dp
      pr%held = .false.
      c = [1.0_dp, -1.0_dp, -1.0_dp]
      do k = 1, pr%n
         associate (p => m%pretensions(k))
            ax = p%axis
            ! springs in proportion to the nodes' consistent shares of the section's area (ring
            ! areas in axisymmetry), so that a uniform stress opens the section uniformly; in
            ! all PENALTY times the section's axial stiffness (the diagonals of its nodes)
            share = area_shares(m, p)
            pr%sections(k)%w = share
            ksum = 0.0_dp
            do i = 1, size(p%nodes)
               ksum = ksum + max(diag(map%id(ax, p%nodes(i))), diag(map%id(ax, p%copies(i))))
            end do
            pr%sections(k)%kp = PENALTY*ksum*share/sum(share)
            pr%kground(k) = sum(pr%sections(k)%kp)
            do i = 1, size(p%nodes)
               if (.not. (pr%sections(k)%kp(i) > 0.0_dp)) cycle
               ke = pr%sections(k)%kp(i)*spread(c, 2, 3)*spread(c, 1, 3)
               ieq = [map%id(ax, p%copies(i)), map%id(ax, p%nodes(i)), map%id(ax, p%ref)]
               call solver%add_element(ieq, ke)
               diag(ieq) = diag(ieq) + pr%sections(k)%kp(i)
               absrow(ieq) = absrow(ieq) + 3.0_dp*pr%sections(k)%kp(i)
            end do
         end associate
      end do
   end subroutine assemble_pretension

   !> Each node's share of the section: the consistent nodal force of a unit
   !! pressure on the edges of the +axis side's elements that lie in the
   !! section.  A share is zero where a node carries nothing of a uniform
   !! stress (the axis corner of a quadratic edge in axisymmetry, a node whose
   !! edges leave the section): it gets no spring.
   pure function area_shares(m, p) result(share)
      type(model_t), intent(in) :: m
      type(pretension_t), intent(in) :: p
      real(dp), allocatable :: share(:)
      real(dp) :: eforce(6), edcod(2, 3), one(3), zero(3)
      integer :: j, ie, iedge, local(3), nn, q, i, gn(3)
      allocate (share(size(p%nodes)))
      share = 0.0_dp
      one = 1.0_dp
      zero = 0.0_dp
      do j = 1, size(p%plus_elems)
         ie = p%plus_elems(j)
         do iedge = 1, nedges(m%nnode_e(ie))
            call element_edge_nodes(m%nnode_e(ie), iedge, local, nn)
            gn(1:nn) = m%lnods(local(1:nn), ie)
            if (.not. all([(any(p%copies == gn(q)), q=1, nn)])) cycle
            edcod(:, 1:nn) = m%coord(:, gn(1:nn))
            call edge_load(m%ntype, nn, edcod(:, 1:nn), one(1:nn), zero(1:nn), &
                           m%mats(m%matno(ie))%thick, &
                           eforce(1:2*nn))
            do q = 1, nn
               do i = 1, size(p%nodes)
                  if (p%copies(i) == gn(q)) share(i) = share(i) + abs(eforce(2*(q - 1) + p%axis))
               end do
            end do
         end do
      end do
   end function area_shares

   !> The section's shortening for displacements u: the mean of the closures
   !! (u_orig - u_copy along the axis) weighted by the nodes' shares -- the
   !! displacement work-conjugate to the force across the section; the
   !! reference node's -delta less the springs' own stretch.
   pure real(dp) function section_shortening(p, w, u) result(s)
      type(pretension_t), intent(in) :: p
      real(dp), intent(in) :: w(:)          !! (nodes) the shares (section_springs_t%w)
      real(dp), intent(in) :: u(:, :)
      s = sum(w*(u(p%axis, p%nodes) - u(p%axis, p%copies)))/sum(w)
   end function section_shortening

   !> The springs' internal nodal forces (K_spring u) for displacements disp,
   !! added to f (2, npoin).
   pure subroutine pretension_nodal_forces(m, pr, disp, f)
      type(model_t), intent(in) :: m
      type(pretension_run_t), intent(in) :: pr
      real(dp), intent(in) :: disp(:, :)
      real(dp), intent(inout) :: f(:, :)
      integer :: k, i, ax
      real(dp) :: g
      do k = 1, pr%n
         associate (p => m%pretensions(k))
            ax = p%axis
            do i = 1, size(p%nodes)
               g = disp(ax, p%copies(i)) - disp(ax, p%nodes(i)) - disp(ax, p%ref)
               g = pr%sections(k)%kp(i)*g
               f(ax, p%copies(i)) = f(ax, p%copies(i)) + g
               f(ax, p%nodes(i)) = f(ax, p%nodes(i)) - g
               f(ax, p%ref) = f(ax, p%ref) - g
            end do
         end associate
      end do
   end subroutine pretension_nodal_forces

   !> The force across every section (tension positive) from the internal
   !! nodal forces K_e u_e of the elements at the cut: on the +axis side
   !! (force_plus = -sum of their axial components at the copies) and on the
   !! -axis side (force_minus = +sum at the originals); the two agree when no
   !! load acts on the section's nodes.  In axisymmetry ring totals.
   subroutine section_forces(m, disp, force_plus, force_minus, status)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: disp(:, :)             !! (2, npoin) total displacements
      real(dp), allocatable, intent(out) :: force_plus(:), force_minus(:)
      type(status_t), intent(inout) :: status
      integer :: k, j
      allocate (force_plus(size(m%pretensions)), force_minus(size(m%pretensions)))
      do k = 1, size(m%pretensions)
         associate (p => m%pretensions(k))
            force_plus(k) = 0.0_dp
            force_minus(k) = 0.0_dp
            do j = 1, size(p%plus_elems)
               force_plus(k) = force_plus(k) - cut_sum(p%plus_elems(j), p%copies, p%axis)
               if (.not. status%ok()) return
            end do
            do j = 1, size(p%minus_elems)
               force_minus(k) = force_minus(k) + cut_sum(p%minus_elems(j), p%nodes, p%axis)
               if (.not. status%ok()) return
            end do
         end associate
      end do
   contains
      !> Sum of the axial internal forces of element ie at the nodes `at`.
      real(dp) function cut_sum(ie, at, ax) result(s)
         integer, intent(in) :: ie, at(:), ax
         real(dp) :: estif(2*MAX_NODE, 2*MAX_NODE), ue(2*MAX_NODE), fe(2*MAX_NODE)
         integer :: nn, i, ierr, imat
         s = 0.0_dp
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         call element_stiffness(m%ntype, nn, m%coord(:, m%lnods(1:nn, ie)), m%mats(imat)%young, &
                                m%mats(imat)%poiss, m%mats(imat)%thick, m%ngaus, &
                                estif(1:2*nn, 1:2*nn), ierr)
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)// &
                            ': no stiffness for the pretension force')
            return
         end if
         ue(1:2*nn) = reshape(disp(:, m%lnods(1:nn, ie)), [2*nn])
         fe(1:2*nn) = matmul(estif(1:2*nn, 1:2*nn), ue(1:2*nn))
         do i = 1, nn
            if (any(at == m%lnods(i, ie))) s = s + fe(2*(i - 1) + ax)
         end do
      end function cut_sum
   end subroutine section_forces
end module pretension_assembly
