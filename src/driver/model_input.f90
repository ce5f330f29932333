!> Input of a model: read the deck, then define what reading only stored.
!!
!! `read_model` is the one entry from a deck file to a model ready for the
!! analysis:
!!
!! 1. `read_deck` (io/) reads every block into the model and returns; it
!!    knows the model layer only, so the CONTACT block stays the deck's
!!    contact specification (model/contact_spec), constants in input units.
!! 2. The Gauss rule asked for on the control card is checked against the
!!    elements of a gmsh mesh (the deck's own elements are checked on the
!!    control card already).
!! 3. `define_contact` (contact/) builds the pairs, lumped areas and R per
!!    pair and converts the constants to model units, when the CONTACT block
!!    was read without errors (nor any before it) and the mesh passed 2.
!! 4. With no error so far, the checks that need the whole model and the
!!    element kernels: the Jacobian of every element, nodes of no element,
!!    rigid reference nodes in axisymmetry, and rigid-body motion of every
!!    body (bodies joined by ties and contact pairs count as one).
!!
!! 5. With no error so far, the start pressure of the rough interfaces: a
!!    displacement-driven first increment needs CONTACT START PM.
!!
!! Every step reports into the same error list with the file and line (and
!! column where the reader knows it), so a rejected deck gives the same
!! messages whichever step found the problem.
module model_input
   use kinds, only: dp
   use errors, only: error_list_t, status_t, STAT_INPUT
   use strings, only: itoa, rtoa
   use model, only: model_t, MAX_NODE, NTYPE_AXISYMMETRIC
   use contact_spec, only: is_rigid_reference
   use restraint_check, only: unrestrained_bodies
   use quadrature, only: valid_ngaus
   use solid2d, only: min_jacobian
   use deck_reader, only: read_deck
   use contact_definition, only: define_contact
   use pretension_section, only: define_pretensions, is_pretension_reference, pretension_links
   use contact_algorithm, only: contact_state_t
   use contact_start, only: init_contact_states, start_pressure
   use assembly, only: assemble_load_cases
   implicit none
   private

   public :: read_model, check_model

contains

   !> Read a deck and define the model it describes.  On return
   !! `errors%n == 0` means `m` is complete, valid and ready for the analysis.
   subroutine read_model(path, m, errors, warnings)
      character(len=*), intent(in) :: path           !! deck file
      type(model_t), intent(out) :: m
      type(error_list_t), intent(out) :: errors      !! input errors (fatal)
      type(error_list_t), intent(out) :: warnings    !! remarks that do not stop the run
      integer :: n0

      call read_deck(path, m, errors, warnings)
      n0 = errors%n
      ! pretension sections: nodes duplicated before the contact surfaces are built
      if (errors%n == 0) call define_pretensions(m, errors)
      n0 = errors%n
      call check_gauss_rules(m, errors)
      if (m%contact_spec%complete .and. errors%n == n0) call define_contact(m, errors, warnings)
      if (errors%n == 0) call check_model(m, errors)
      if (errors%n == 0) call check_start_pressure(m, errors)
   end subroutine read_model

   !> A rough interface needs the start pressure p_m of eq. (4.1): from the
   !! force of the first increment normal to the initially closed pairs, or
   !! from CONTACT START PM.  A first increment that applies no such force (it
   !! is displacement-driven) leaves p_m undefined: an input error, located at
   !! the CONTACT block, found here rather than by the analysis.
   !! Ref: Altenbach & Buczkowski, eq. (4.1).
   subroutine check_start_pressure(m, errors)
      type(model_t), intent(in) :: m
      type(error_list_t), intent(inout) :: errors
      type(contact_state_t) :: st
      type(status_t) :: status
      real(dp), allocatable :: fcase(:, :, :), ucase(:, :, :)
      if (size(m%contact%pairs) == 0 .or. m%contact%opts%p_start > 0.0_dp) return
      call init_contact_states(m, st)
      if (.not. st%has_rough) return
      call assemble_load_cases(m, fcase, ucase, status)
      if (.not. status%ok()) return      ! the analysis reports it, with the element
      call start_pressure(m, fcase, m%lambda(:, 1) - m%lambda(:, 0), st, status)
      if (status%code == STAT_INPUT) call errors%add('E-START', status%message, file=m%deck_file, &
                                                     line=max(m%contact_spec%line, 1))
   end subroutine check_start_pressure

   !> NGAUS of the control card against the elements of a gmsh mesh (MESH
   !! block): reported at the first element whose family has no such rule.
   subroutine check_gauss_rules(m, errors)
      type(model_t), intent(in) :: m
      type(error_list_t), intent(inout) :: errors
      integer :: ie, nn
      if (.not. allocated(m%mesh_file) .or. .not. allocated(m%nnode_e)) return
      if (m%ngaus == 0) return
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         if (.not. valid_ngaus(nn, m%ntype, m%ngaus)) then
            call errors%add('E-GMSH', 'NGAUS = '//itoa(m%ngaus)// &
                            ' on the control card is not valid for the '// &
                            itoa(nn)//'-node elements of the mesh (use 0 for the default rules)', &
                            file=m%mesh_file, line=m%elem_line(ie))
            return
         end if
      end do
   end subroutine check_gauss_rules

   !> Checks that need the whole model: geometry of every element, nodes that
   !! belong to no element, the rigid reference nodes of an axisymmetric
   !! model, and rigid-body motion of every body (after the contact
   !! definition: its pairs join bodies).
   subroutine check_model(m, errors)
      type(model_t), intent(in) :: m
      type(error_list_t), intent(inout) :: errors
      integer :: ie, nn, ip, k, nbad
      real(dp) :: jmin, elcod(2, MAX_NODE), size2
      logical, allocatable :: used(:)
      integer, allocatable :: bad_node(:), nolinks(:, :), plinks(:, :)
      character(len=80), allocatable :: what(:)
      character(len=:), allocatable :: msg
      integer :: n0

      n0 = errors%n
      allocate (used(m%npoin))
      used = .false.
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         elcod(:, 1:nn) = m%coord(:, m%lnods(1:nn, ie))
         used(m%lnods(1:nn, ie)) = .true.
         size2 = maxval(elcod(1, 1:nn)) - minval(elcod(1, 1:nn)) + maxval(elcod(2, 1:nn)) - &
               minval(elcod(2, 1:nn))
         jmin = min_jacobian(nn, elcod(:, 1:nn))
         if (.not. (jmin > 1.0e-12_dp*size2**2)) then
            msg = 'ELEMENTS: element '//itoa(ie)//' is '
            if (jmin < -1.0e-12_dp*size2**2) then
               msg = msg//'inverted or distorted (Jacobian determinant '//rtoa(jmin)// &
                     ' < 0; corner nodes must be numbered anticlockwise, midside nodes near the &
                     &middle of their edges)'
            else
               msg = msg//'degenerate (zero area: Jacobian determinant '//rtoa(jmin)//')'
            end if
            if (allocated(m%mesh_file)) then
               call errors%add('E-GEOMETRY', msg, file=m%mesh_file, line=m%elem_line(ie))
            else
               call errors%add('E-GEOMETRY', msg, file=m%deck_file, line=m%elem_line(ie), col=11)
            end if
         end if
      end do
      do ip = 1, m%npoin
         if (.not. used(ip) .and. .not. is_rigid_reference(m%contact_spec, ip) .and. &
             .not. is_pretension_reference(m, ip)) then
            if (allocated(m%mesh_file)) then
               ! an extra node of a MESH block (NODE card): the only nodes of no element there
               call errors%add('E-UNUSED', 'MESH/NODE: extra node '//itoa(ip)// &
                               ' is the reference node of no '// &
                               'rigid body (CONTACT, RIGID): its displacement would be &
                               &undetermined', &
                               file=m%deck_file, line=m%node_line(ip), col=1)
               cycle
            end if
            call errors%add('E-UNUSED', 'NODES: node '//itoa(ip)//' belongs to no element '// &
                            '(its displacement would be undetermined; only the reference node of a &
                            &rigid body '// &
                            'in CONTACT may be a node of no element)', file=m%deck_file, &
                            line=m%node_line(ip), col=1)
         end if
      end do
      if (m%ntype == NTYPE_AXISYMMETRIC) then
         do k = 1, size(m%fixes)
            if (.not. is_rigid_reference(m%contact_spec, m%fixes(k)%node)) cycle
            if (abs(m%fixes(k)%value(1)) > 0.0_dp) call &
                  errors%add('E-RIGID', 'RESTRAINTS: node '// &
                itoa(m%fixes(k)%node)// &
                ' is the reference node of a rigid body, which can only move axially '// &
                'in an axisymmetric model: its radial displacement must be 0, found UX = '// &
                rtoa(m%fixes(k)%value(1)), file=m%deck_file, line=m%fixes(k)%line, col=11)
         end do
      end if
      if (errors%n > n0) return

      ! bodies joined by ties, contact pairs or pretension sections are checked together
      call pretension_links(m, plinks)
      allocate (nolinks(2, size(m%ties, 2) + size(m%contact%pairs) + size(plinks, 2)))
      nolinks(:, size(m%ties, 2) + size(m%contact%pairs) + 1:) = plinks
      do k = 1, size(m%ties, 2)
         nolinks(:, k) = m%ties(1:2, k)
      end do
      do k = 1, size(m%contact%pairs)
         nolinks(:, size(m%ties, 2) + k) = [m%contact%pairs(k)%node_a, m%contact%pairs(k)%node_b]
      end do
      call unrestrained_bodies(m, nolinks, nbad, bad_node, what)
      do k = 1, nbad
         call errors%add('E-UNRESTRAINED', &
                         'RESTRAINTS: unrestrained model: the body containing node '// &
                         itoa(bad_node(k))//' is free to move as a rigid body ('//trim(what(k))// &
                         '); add restraints that prevent it', file=m%deck_file, &
                         line=max(m%restraints_line, 1))
      end do
   end subroutine check_model
end module model_input
