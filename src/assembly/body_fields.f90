!> The bodies' fields after a step, element by element: stresses at every
!! Gauss point and averaged at the nodes, the support reactions, and the
!! equilibrium check of every body.
!!
!! Fills the body fields record (model layer) that the result file and the
!! listing read.  The Gauss-point layout (gp_start, xygp) is fixed: the first
!! call lays it out.  Ref: Hinton & Owen (1977), STRESS (stresses at the Gauss
!! points), nodal averaging of the element extrapolations.
module body_fields
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: status_t, STAT_JACOBIAN, STAT_NONFINITE
   use strings, only: itoa, rtoa
   use model, only: model_t, MAX_NODE
   use contact_types, only: PAIR_RIGID
   use restraint_check, only: find_bodies
   use dof_map, only: dof_map_t
   use records, only: body_fields_t
   use quadrature, only: max_gp
   use solid2d, only: element_stresses
   use assembly, only: coupling_t, restrained_forces, element_error
   use error_estimate, only: estimate_error   ! re-exported: the estimate
                                              ! of the fields recovered here
   implicit none
   private
   public :: recover_stresses, update_reactions, number_bodies, body_imbalance, zero_fields, &
         stiffness_range
   public :: estimate_error

contains

   !> Stresses at every Gauss point and averaged at the nodes for the
   !! displacements body%disp.  The first call lays out the Gauss points
   !! (gp_start, xygp) and allocates the stress arrays.
   subroutine recover_stresses(m, body, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(inout) :: body
      type(status_t), intent(inout) :: status
      real(dp) :: elcod(2, MAX_NODE), eldis(2*MAX_NODE), xyg(2, max_gp), sg(4, max_gp), &
            sn(4, MAX_NODE)
      real(dp), allocatable :: cnt(:)
      integer :: ie, nn, ngp, ierr, k, imat

      if (.not. allocated(body%gp_start)) call lay_out_gauss_points(m, body)
      body%estimated = .false.   ! (until estimate_error has seen these stresses)
      allocate (cnt(m%npoin))
      cnt = 0.0_dp
      body%sig_nd = 0.0_dp
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         do k = 1, nn
            eldis(2*k - 1:2*k) = body%disp(:, m%lnods(k, ie))
         end do
         call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                               m%mats(imat)%poiss, &
                               m%ngaus, eldis(1:2*nn), ngp, xyg, sg, sn(:, 1:nn), ierr)
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)//' (stress recovery): '// &
                            element_error(ierr))
            return
         end if
         body%xygp(:, body%gp_start(ie):body%gp_start(ie + 1) - 1) = xyg(:, 1:ngp)
         body%sig_gp(:, body%gp_start(ie):body%gp_start(ie + 1) - 1) = sg(:, 1:ngp)
         do k = 1, nn
            body%sig_nd(:, m%lnods(k, ie)) = body%sig_nd(:, m%lnods(k, ie)) + sn(:, k)
            cnt(m%lnods(k, ie)) = cnt(m%lnods(k, ie)) + 1.0_dp
         end do
      end do
      do k = 1, m%npoin
         if (cnt(k) > 0.0_dp) body%sig_nd(:, k) = body%sig_nd(:, k)/cnt(k)
      end do
   end subroutine recover_stresses

   !> Body fields of the model at rest: displacements, reactions and stresses
   !! zero, no dof restrained yet, the Gauss points laid out.  For the start
   !! of a run, and for the result file of a run that stopped before its
   !! first increment.
   subroutine zero_fields(m, body)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(inout) :: body
      if (.not. allocated(body%disp)) allocate (body%disp(2, m%npoin))
      if (.not. allocated(body%react)) allocate (body%react(2, m%npoin))
      if (.not. allocated(body%restrained)) allocate (body%restrained(2, m%npoin))
      if (.not. allocated(body%gp_start)) call lay_out_gauss_points(m, body)
      body%disp = 0.0_dp
      body%react = 0.0_dp
      body%restrained = .false.
      body%sig_nd = 0.0_dp
      body%sig_gp = 0.0_dp
      if (.not. allocated(body%error_indicator)) allocate (body%error_indicator(m%nelem))
      body%error_indicator = 0.0_dp
      body%estimated_error = 0.0_dp
      body%error_norm = 0.0_dp
      body%energy_norm = 0.0_dp
      body%estimated = .false.
   end subroutine zero_fields

   !> The bodies' stiffness K_AB in the range a factorization works in.  A
   !! non-finite diagonal (a modulus or thickness that overflows) stops the
   !! run (STAT_NONFINITE).  When a factorization has failed (status not ok
   !! on entry) and the diagonal exceeds sqrt(huge) -- the elimination forms
   !! products of two entries -- the message names the stiffness instead of
   !! blaming the restraints.
   subroutine stiffness_range(map, diag, status)
      type(dof_map_t), intent(in) :: map       !! equation numbers (names the node and dof)
      real(dp), intent(in) :: diag(:)          !! (neq) diagonal of K_AB [force/length]
      type(status_t), intent(inout) :: status
      integer :: ieq
      if (size(diag) == 0) return
      if (.not. all(ieee_is_finite(diag))) then
         ieq = findloc(ieee_is_finite(diag), .false., 1)
         call status%set(STAT_NONFINITE, &
                         'the bodies'' stiffness matrix holds non-finite numbers (its diagonal '// &
                         'term at '//map%describe(ieq)// &
                         '): a material''s E or thickness overflows double '// &
                         'precision; check them and their units')
      else if (.not. status%ok()) then
         ieq = maxloc(abs(diag), 1)
         if (abs(diag(ieq)) <= sqrt(huge(1.0_dp))) return
         call status%set(STAT_NONFINITE, &
                         'the bodies'' stiffness matrix is out of the range of double &
                         &precision '// &
                         '(its diagonal term '//rtoa(diag(ieq))//' at '//map%describe(ieq)// &
                         ' exceeds sqrt(huge) = '// &
                         rtoa(sqrt(huge(1.0_dp)))//'; the factorization reported: '// &
                         status%message// &
                         '): check the materials'' E and thickness and their units')
      end if
   end subroutine stiffness_range

   !> Count the Gauss points of every element; allocate the Gauss-point and
   !! nodal stress arrays.
   subroutine lay_out_gauss_points(m, body)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(inout) :: body
      real(dp) :: elcod(2, MAX_NODE), xyg(2, max_gp), sg(4, max_gp), sn(4, MAX_NODE)
      integer :: ie, nn, ngp, ierr, k, imat, ntot
      allocate (body%gp_start(m%nelem + 1))
      body%gp_start(1) = 1
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         imat = m%matno(ie)
         call element_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                               m%mats(imat)%poiss, &
                               m%ngaus, [(0.0_dp, k=1, 2*nn)], ngp, xyg, sg, sn(:, 1:nn), ierr)
         body%gp_start(ie + 1) = body%gp_start(ie) + ngp
      end do
      ntot = body%gp_start(m%nelem + 1) - 1
      if (allocated(body%xygp)) deallocate (body%xygp)
      if (allocated(body%sig_gp)) deallocate (body%sig_gp)
      if (allocated(body%sig_nd)) deallocate (body%sig_nd)
      allocate (body%xygp(2, ntot), body%sig_gp(4, ntot), body%sig_nd(4, m%npoin))
   end subroutine lay_out_gauss_points

   !> Support reactions K u - f_ext at the restrained dofs, zero elsewhere:
   !! the bodies' restrained forces plus the springs' nodal forces fsp (what
   !! the springs take from the bodies) minus the external forces.
   subroutine update_reactions(coup, map, fext, fsp, body)
      type(coupling_t), intent(in) :: coup
      type(dof_map_t), intent(in) :: map
      real(dp), intent(in) :: fext(:, :)       !! (2, npoin) external forces of the step
      real(dp), intent(in) :: fsp(:, :)        !! (2, npoin) spring forces at the nodes
      type(body_fields_t), intent(inout) :: body
      real(dp), allocatable :: fr(:, :)
      allocate (fr(2, size(fext, 2)))
      call restrained_forces(coup, map, body%disp, fr)
      body%react = 0.0_dp
      where (body%restrained) body%react = fr + fsp - fext
   end subroutine update_reactions

   !> The body of every node in each direction (0: none), for the
   !! equilibrium check.  A rigid body's reference node belongs to no
   !! element: a body of its own.  Bodies joined by TIES exchange forces
   !! through the tied dofs: for the direction of a tie they are one body
   !! (the tie force is internal to it), for the other direction they stay
   !! apart (a tie of the x dofs carries no y force).
   subroutine number_bodies(m, body, nbody)
      type(model_t), intent(in) :: m
      integer, allocatable, intent(out) :: body(:, :)   !! (2, npoin) body of every
                                                        !! node, x and y balance
      integer, intent(out) :: nbody                      !! bodies (the larger count
                                                         !! of the two directions)
      integer, allocatable :: mesh_body(:), links(:, :), rigid(:)
      integer :: j, idir, nmesh, nlink, k, nb(2)
      allocate (mesh_body(m%npoin), body(2, m%npoin), rigid(m%npoin))
      call find_bodies(m, reshape([integer ::], [2, 0]), mesh_body, nmesh)
      ! reference nodes of rigid bodies: a body of their own in both directions
      rigid = 0
      do j = 1, size(m%contact%pairs)
         if (m%contact%pairs(j)%kind /= PAIR_RIGID) cycle
         if (mesh_body(m%contact%pairs(j)%node_b) > 0) cycle
         rigid(m%contact%pairs(j)%node_b) = 1
      end do
      do idir = 1, 2
         nlink = 0
         if (allocated(m%ties)) nlink = count(m%ties(3, :) == idir)
         allocate (links(2, nlink))
         k = 0
         do j = 1, nlink_total()
            if (m%ties(3, j) /= idir) cycle
            k = k + 1
            links(:, k) = m%ties(1:2, j)
         end do
         call find_bodies(m, links, body(idir, :), nb(idir))
         deallocate (links)
         do j = 1, m%npoin
            if (rigid(j) == 0 .or. body(idir, j) > 0) cycle
            nb(idir) = nb(idir) + 1
            body(idir, j) = nb(idir)
         end do
      end do
      nbody = maxval(nb)
   contains
      integer function nlink_total()
         nlink_total = 0
         if (allocated(m%ties)) nlink_total = size(m%ties, 2)
      end function nlink_total
   end subroutine number_bodies

   !> Largest |sum of the forces on a body| relative to the force scale of the run.
   !! In axisymmetry only the axial resultant must vanish: the radial ring forces
   !! of a body in equilibrium do not add up to zero (its hoop stresses carry them).
   pure real(dp) function body_imbalance(body, nbody, f, scale, axisymmetric) result(worst)
      integer, intent(in) :: body(:, :)      !! (2, npoin) body of every node
                                             !! for the x and y balance
      integer, intent(in) :: nbody           !! bodies (at least the largest entry of body)
      real(dp), intent(in) :: f(:, :)        !! (2, npoin) external + reactions
                                             !! - spring internal forces
      real(dp), intent(in) :: scale          !! largest nodal force seen so far
      logical, intent(in) :: axisymmetric    !! check the axial (z) resultant only
      real(dp) :: total(2, max(nbody, 1))
      integer :: ip, idir
      total = 0.0_dp
      do ip = 1, size(body, 2)
         do idir = 1, 2
            if (body(idir, ip) > 0) then
               total(idir, body(idir, ip)) = total(idir, body(idir, ip)) + f(idir, ip)
            end if
         end do
      end do
      if (axisymmetric) then
         worst = maxval(abs(total(2, :)))/scale
      else
         worst = maxval(abs(total))/scale
      end if
   end function body_imbalance
end module body_fields
