!> Hinton–Owen style reader of Kontakt2D input decks.
!!
!! Blocks come in a fixed order, each introduced by a keyword card:
!!
!!     TITLE, CONTROL, [OPTIONS], [MESH], ELEMENTS, NODES, RESTRAINTS, [TIES],
!!     MATERIALS, [LOADS], [CONTACT], [INCREMENTS], END
!!
!! One reader routine per block (CalculiX style).  Every problem is collected
!! in the deck's error list with file, line, column, the card's name, what was
!! expected and what was found; reading goes on after an error so that one run
!! shows as many errors as possible.  The format is specified in
!! docs/deck-format.md, which this module follows column for column.
!!
!! The reader knows the model only: it stores what the deck says (the CONTACT
!! block as the model's contact specification) and returns.  The contact
!! definition and the checks that need the element kernels (Jacobians, rigid
!! body motion) run after it, in driver/model_input (`read_model`), and report
!! into the same error list.
!!
!! Ref: E. Hinton, D. R. J. Owen, *Finite Element Programming*, 1977, routine INPUT.
!!
!! This module owns the order of the blocks, the dispatch to their readers and
!! the completion of the model (`finish_model`).  The blocks are read in rooms
!! of their own: deck_blocks (block table, card helpers), deck_control_cards
!! (TITLE, CONTROL, OPTIONS), mesh_block (MESH), deck_geometry_cards
!! (ELEMENTS, NODES, RESTRAINTS), deck_contact (TIES, CONTACT),
!! deck_material_cards (MATERIALS), deck_load_cards (LOADS, INCREMENTS).
module deck_reader
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, restraint_t, NTYPE_AXISYMMETRIC
   use contact_spec, only: is_rigid_reference
   use deck_contact, only: read_ties, read_contact
   use mesh_block, only: read_mesh_block
   use deck_blocks, only: block_order, block_index, is_block_card, skip_to_block
   use deck_control_cards, only: control_t, read_title, read_control, read_options
   use deck_geometry_cards, only: read_elements, read_nodes, read_restraints
   use deck_material_cards, only: read_materials
   use deck_load_cards, only: read_loads, read_increments
   implicit none
   private

   public :: read_deck, block_order

   !> ELEMENTS and NODES are not required when a MESH block gives the mesh (see `required`).
   logical, parameter :: block_required(13) = [.true., .true., .false., .false., .true., .true., &
                                               .true., .false., .true., .false., .false., .false., &
                                               .true.]

contains

   !> Read and check a deck.  On return `errors%n == 0` means `m` is complete and valid.
   subroutine read_deck(path, m, errors, warnings)
      character(len=*), intent(in) :: path
      type(model_t), intent(out) :: m
      type(error_list_t), intent(out) :: errors     !! input errors (fatal)
      type(error_list_t), intent(out) :: warnings   !! remarks that do not stop the run
      type(deck_t) :: d
      type(control_t) :: ctl
      logical :: loaded, seen(size(block_order))
      integer :: ic, iblk, last, k
      character(len=:), allocatable :: kw

      call d%load(path, loaded)
      m%deck_file = path
      m%title = ''
      m%solver_name = 'AUTO'
      m%listing_level = 'SHORT'
      m%renumber = 'AUTO'
      m%condense = 'AUTO'
      allocate (m%fixes(0), m%point_loads(0), m%edge_loads(0), m%body_loads(0), m%mats(0), &
                m%ties(3, 0), m%pretensions(0))
      allocate (m%contact%ifaces(0), m%contact%pairs(0))
      if (.not. loaded) then
         errors = d%errors
         return
      end if
      if (d%ncard == 0) then
         call d%error_eof('E-EMPTY', 'the deck is empty: expected a TITLE block first')
         errors = d%errors
         return
      end if

      seen = .false.
      last = 0
      do while (.not. d%at_end())
         ic = d%next()
         kw = d%keyword(ic)
         iblk = block_index(kw)
         if (.not. d%is_keyword_card(ic) .or. iblk == 0) then
            call d%error_at(ic, 1, 'E-BLOCK', 'expected a block keyword (TITLE, CONTROL, '// &
                            'OPTIONS, MESH, ELEMENTS, NODES, RESTRAINTS, TIES, MATERIALS, '// &
                            'LOADS, CONTACT, INCREMENTS or END), found "'// &
                            shown(trim(d%cards(ic)%text))//'"')
            call skip_to_block(d)
            cycle
         end if
         if (seen(iblk)) then
            call d%error_at(ic, 1, 'E-BLOCK', 'block '//trim(kw)//' appears twice')
            call skip_to_block(d)
            cycle
         end if
         if (iblk < last) then
            call d%error_at(ic, 1, 'E-ORDER', 'block '//trim(kw)// &
                            ' is out of order: it must come before '//trim(block_order(last))// &
                            ' (order: TITLE, CONTROL, OPTIONS, MESH, ELEMENTS, NODES, '// &
                            'RESTRAINTS, TIES, MATERIALS, LOADS, CONTACT, INCREMENTS, END)')
            call skip_to_block(d)
            cycle
         end if
         ! required blocks skipped over
         do k = last + 1, iblk - 1
            if (required(k) .and. .not. seen(k)) then
               call d%error_at(ic, 1, 'E-MISSING-BLOCK', 'missing block '//trim(block_order(k))// &
                               ': expected it before '//trim(kw))
            end if
         end do
         seen(iblk) = .true.
         last = iblk
         if (kw == 'END') then
            if (.not. d%at_end()) then
               ic = d%next()
               call d%error_at(ic, 1, 'E-AFTER-END', 'nothing may follow the END card, found "'// &
                               shown(trim(d%cards(ic)%text))//'"')
            end if
            exit
         end if
         call read_block(d, ic, kw, m, ctl, seen, warnings)
      end do

      do k = 1, size(block_order)
         if (required(k) .and. .not. seen(k) .and. k > last) then
            call d%error_eof('E-MISSING-BLOCK', 'missing block '//trim(block_order(k))// &
                             ' (the deck ended before it; every deck ends with an END card)')
         end if
      end do

      if (ctl%ok) call finish_model(m)
      errors = d%errors
   contains
      !> Whether block k must appear: ELEMENTS and NODES not after a MESH block.
      logical function required(k)
         integer, intent(in) :: k
         required = block_required(k)
         if (seen(block_index('MESH')) .and. (block_order(k) == 'ELEMENTS' .or. &
             block_order(k) == 'NODES')) then
            required = .false.
         end if
      end function required
   end subroutine read_deck

   !> Read block kw, whose keyword card is ic, if the blocks it needs were read.
   subroutine read_block(d, ic, kw, m, ctl, seen, warnings)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      character(len=*), intent(in) :: kw               !! the block keyword
      type(model_t), intent(inout) :: m
      type(control_t), intent(inout) :: ctl
      logical, intent(in) :: seen(:)                   !! blocks seen so far (this one included)
      type(error_list_t), intent(inout) :: warnings
      ! a block whose prerequisites failed cannot be checked meaningfully: skipped
      select case (trim(kw))
      case ('TITLE')
         call read_title(d, ic, m)
      case ('CONTROL')
         call read_control(d, ic, m, ctl)
      case ('OPTIONS')
         call read_options(d, m)
      case ('MESH')
         call start_mesh_block(d, ic, m, ctl)
      case ('ELEMENTS')
         if (.not. ctl%ok) then
            call skip_to_block(d)
         else if (mesh_conflict(d, ic, ctl, seen)) then
            call skip_to_block(d)
         else
            call read_elements(d, ic, m)
         end if
      case ('NODES')
         if (.not. ctl%ok) then
            call skip_to_block(d)
         else if (mesh_conflict(d, ic, ctl, seen)) then
            call skip_to_block(d)
         else
            call read_nodes(d, ic, m)
         end if
      case ('RESTRAINTS')
         m%restraints_line = d%cards(ic)%line
         if (ctl%ok) then
            call read_restraints(d, ic, m, ctl%nvfix)
         else
            call skip_to_block(d)
         end if
      case ('TIES')
         if (ctl%ok .and. allocated(m%coord)) then
            call read_ties(d, m, is_block_card)
         else
            call skip_to_block(d)
         end if
      case ('CONTACT')
         if (ctl%ok .and. allocated(m%coord) .and. allocated(m%lnods) .and. &
             allocated(m%mats) .and. d%errors%n == 0) then
            call read_contact(d, ic, m, is_block_card)
         else
            call skip_to_block(d)
         end if
      case ('MATERIALS')
         if (ctl%ok) then
            call read_materials(d, ic, m, warnings)
         else
            call skip_to_block(d)
         end if
      case ('LOADS')
         if (ctl%ok) then
            call read_loads(d, m)
         else
            call skip_to_block(d)
         end if
      case ('INCREMENTS')
         call read_increments(d, m)
      end select
   end subroutine read_block

   !> MESH block: only with NPOIN = NELEM = 0 on the control card (see mesh_block).
   subroutine start_mesh_block(d, ic, m, ctl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(inout) :: m
      type(control_t), intent(inout) :: ctl
      if (.not. ctl%ok) then
         call skip_to_block(d)
      else if (.not. ctl%counts_from_mesh) then
         call d%error_at(ic, 1, 'E-MESH', 'MESH: the mesh comes from the .msh file, so NPOIN '// &
                         'and NELEM on the control card (line '//itoa(ctl%line)// &
                         ') must be blank or 0')
         call skip_to_block(d)
         ctl%ok = .false.
      else
         call read_mesh_block(d, ic, m, m%nnode, is_block_card, ctl%ok)
      end if
   end subroutine start_mesh_block

   !> ELEMENTS or NODES after a MESH block, or without the counts they need.
   logical function mesh_conflict(d, ic, ctl, seen)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(control_t), intent(in) :: ctl
      logical, intent(in) :: seen(:)
      mesh_conflict = .true.
      if (seen(block_index('MESH'))) then
         call d%error_at(ic, 1, 'E-BLOCK', 'block '//d%keyword(ic)// &
                         ' cannot be given with a MESH block: the mesh comes from the .msh file')
      else if (ctl%counts_from_mesh) then
         call d%error_at(ic, 1, 'E-CONTROL', 'CONTROL: NPOIN and NELEM are 0 or blank on the '// &
                         'control card (line '//itoa(ctl%line)// &
                         '): give them, or take the mesh from a MESH block')
      else
         mesh_conflict = .false.
      end if
   end function mesh_conflict

   ! ------------------------------------------------------------------ checks

   !> Defaults for blocks the deck left out, and the radial restraint of
   !! nodes on the axis in axisymmetric analysis (u_r = 0 there by symmetry;
   !! added unless the deck restrains u_r itself).
   subroutine finish_model(m)
      type(model_t), intent(inout) :: m
      integer :: ip, k, nadd
      real(dp) :: tol
      integer, allocatable :: fix_of(:)
      logical, allocatable :: on_axis(:)
      type(restraint_t), allocatable :: added(:)
      if (m%ntype == NTYPE_AXISYMMETRIC .and. allocated(m%coord)) then
         ! one pass over the restraints (the first card of each node), one over
         ! the nodes, and the new restraints added at once: linear in NPOIN
         allocate (fix_of(m%npoin), on_axis(m%npoin))
         fix_of = 0
         do k = size(m%fixes), 1, -1
            ip = m%fixes(k)%node
            if (ip >= 1 .and. ip <= m%npoin) fix_of(ip) = k
         end do
         tol = 1.0e-12_dp*max(maxval(abs(m%coord)), 1.0e-300_dp)
         do ip = 1, m%npoin
            ! a rigid body's reference node moves axially only: a rigid ring
            ! cannot change its radius (its radial restraint is added like
            ! that of a node on the axis)
            on_axis(ip) = abs(m%coord(1, ip)) <= tol .or. is_rigid_reference(m%contact_spec, ip)
         end do
         do k = 1, size(m%fixes)
            ip = m%fixes(k)%node
            if (ip < 1 .or. ip > m%npoin) cycle
            if (on_axis(ip)) m%fixes(k)%fixed(1) = .true.
         end do
         nadd = count(on_axis .and. fix_of == 0)
         if (nadd > 0) then
            allocate (added(size(m%fixes) + nadd))
            added(1:size(m%fixes)) = m%fixes
            k = size(m%fixes)
            do ip = 1, m%npoin
               if (.not. (on_axis(ip) .and. fix_of(ip) == 0)) cycle
               k = k + 1
               added(k) = restraint_t(node=ip, fixed=[.true., .false.])
            end do
            call move_alloc(added, m%fixes)
         end if
      end if
      if (.not. allocated(m%pretensions)) allocate (m%pretensions(0))
      m%ncase = max(1, &
                    maxval([1, m%fixes%icase, m%point_loads%icase, m%edge_loads%icase, &
                    m%body_loads%icase, m%pretensions%icase]))
      if (m%nincs == 0) then
         m%nincs = 1
         allocate (m%lambda(m%ncase, 0:1))
         m%lambda(:, 0) = 0.0_dp
         m%lambda(:, 1) = 1.0_dp
      end if
   end subroutine finish_model

end module deck_reader
