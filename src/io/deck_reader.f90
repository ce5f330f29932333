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
module deck_reader
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa, upper
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, MAX_CASE, material_t, restraint_t, point_load_t, edge_load_t, &
                    body_load_t, MAX_NODE, NTYPE_AXISYMMETRIC
   use topology, only: element_edge_nodes, nedges
   use contact_spec, only: is_rigid_reference
   use deck_contact, only: read_ties, read_contact
   use pretension, only: pretension_t
   use pretension_cards, only: is_pretension_card, read_pretension_card, read_pretension_nodes, finish_pretensions
   use mesh_block, only: read_mesh_block
   use group_cards, only: is_group_card, read_group_restraint, read_group_point_load, read_group_edge_load, &
                          check_restraint_overlaps
   implicit none
   private

   public :: read_deck, block_order

   !> Block keywords in their required order.
   character(len=10), parameter :: block_order(13) = [character(len=10) :: &
                                   'TITLE', 'CONTROL', 'OPTIONS', 'MESH', 'ELEMENTS', 'NODES', &
                                   'RESTRAINTS', 'TIES', 'MATERIALS', 'LOADS', 'CONTACT', 'INCREMENTS', 'END']
   !> ELEMENTS and NODES are not required when a MESH block gives the mesh (see `required`).
   logical, parameter :: block_required(13) = [.true., .true., .false., .false., .true., .true., &
                                               .true., .false., .true., .false., .false., .false., .true.]

   !> Longest title (characters): it is one attribute of the result file.
   integer, parameter :: MAX_TITLE = 256

   !> Counts declared on the control card, needed by later blocks.
   type :: control_t
      integer :: nvfix = 0
      logical :: ok = .false.
      logical :: counts_from_mesh = .false.   !! NPOIN = NELEM = 0: a MESH block must give the mesh
      integer :: line = 0
   end type control_t

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
      allocate (m%fixes(0), m%point_loads(0), m%edge_loads(0), m%body_loads(0), m%mats(0), m%ties(3, 0), &
                m%pretensions(0))
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
            call d%error_at(ic, 1, 'E-BLOCK', 'expected a block keyword ('// &
                            'TITLE, CONTROL, OPTIONS, MESH, ELEMENTS, NODES, RESTRAINTS, TIES, MATERIALS, '// &
                            'LOADS, CONTACT, INCREMENTS or END), found "'//shown(trim(d%cards(ic)%text))//'"')
            call skip_to_block(d)
            cycle
         end if
         if (seen(iblk)) then
            call d%error_at(ic, 1, 'E-BLOCK', 'block '//trim(kw)//' appears twice')
            call skip_to_block(d)
            cycle
         end if
         if (iblk < last) then
            call d%error_at(ic, 1, 'E-ORDER', 'block '//trim(kw)//' is out of order: it must come before '// &
                            trim(block_order(last))//' (order: TITLE, CONTROL, OPTIONS, MESH, ELEMENTS, '// &
                            'NODES, RESTRAINTS, TIES, MATERIALS, LOADS, CONTACT, INCREMENTS, END)')
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
         if (seen(block_index('MESH')) .and. (block_order(k) == 'ELEMENTS' .or. block_order(k) == 'NODES')) then
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
            call read_restraints(d, ic, m, ctl)
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
         if (ctl%ok .and. allocated(m%coord) .and. allocated(m%lnods) .and. allocated(m%mats) .and. &
             d%errors%n == 0) then
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
         call d%error_at(ic, 1, 'E-MESH', 'MESH: the mesh comes from the .msh file, so NPOIN and NELEM on the '// &
                         'control card (line '//itoa(ctl%line)//') must be blank or 0')
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
         call d%error_at(ic, 1, 'E-BLOCK', 'block '//d%keyword(ic)//' cannot be given with a MESH block: '// &
                         'the mesh comes from the .msh file')
      else if (ctl%counts_from_mesh) then
         call d%error_at(ic, 1, 'E-CONTROL', 'CONTROL: NPOIN and NELEM are 0 or blank on the control card (line '// &
                         itoa(ctl%line)//'): give them, or take the mesh from a MESH block')
      else
         mesh_conflict = .false.
      end if
   end function mesh_conflict

   !> Consume data cards up to (not including) the next block keyword card.
   subroutine skip_to_block(d)
      type(deck_t), intent(inout) :: d
      integer :: ic
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
      end do
   end subroutine skip_to_block

   !> Position of a keyword in `block_order` (0 if it is none).
   !! (A loop, not FINDLOC: gfortran 12 mis-compares deferred-length strings there.)
   pure integer function block_index(kw)
      character(len=*), intent(in) :: kw
      integer :: k
      block_index = 0
      do k = 1, size(block_order)
         if (trim(block_order(k)) == kw) then
            block_index = k
            return
         end if
      end do
   end function block_index

   logical function is_block_card(d, ic)
      type(deck_t), intent(in) :: d
      integer, intent(in) :: ic
      is_block_card = .false.
      if (.not. d%is_keyword_card(ic)) return
      is_block_card = block_index(d%keyword(ic)) > 0
   end function is_block_card

   !> Next data card of the current block, or 0 at the next block keyword.
   !! A card that starts with a letter but is no block keyword is reported.
   integer function next_data_card(d, card, expected, allow_group) result(ic)
      type(deck_t), intent(inout) :: d
      character(len=*), intent(in) :: card      !! card name
      character(len=*), intent(in) :: expected  !! what its first field holds
      logical, intent(in), optional :: allow_group  !! GROUP cards are data cards here (see group_cards)
      ic = 0
      do while (.not. d%at_end())
         if (is_block_card(d, d%peek())) return
         ic = d%next()
         if (present(allow_group)) then
            if (allow_group .and. is_group_card(d, ic)) return
         end if
         if (d%is_keyword_card(ic)) then
            ! an unknown keyword: report it once and skip its cards
            call d%error_at(ic, 1, 'E-BLOCK', card//': expected '//expected// &
                            ' or a block keyword (TITLE, CONTROL, OPTIONS, MESH, ELEMENTS, NODES, RESTRAINTS, '// &
                            'TIES, MATERIALS, LOADS, CONTACT, INCREMENTS, END), found "'//shown(trim(d%cards(ic)%text))//'"')
            call skip_to_block(d)
            ic = 0
            return
         end if
         return
      end do
   end function next_data_card

   ! ------------------------------------------------------------------ TITLE

   subroutine read_title(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic
      if (d%at_end()) then
         call d%error_at(ickw, 1, 'E-TITLE', 'TITLE: expected a title card after the keyword, found the end of the file')
         return
      end if
      ic = d%peek()
      if (is_block_card(d, ic)) then
         call d%error_at(ic, 1, 'E-TITLE', 'TITLE: expected a title card (one line of text), found the block keyword '// &
                         d%keyword(ic))
         return
      end if
      ic = d%next()
      m%title = trim(adjustl(d%cards(ic)%text))
      if (len(m%title) > MAX_TITLE) then
         call d%error_at(ic, MAX_TITLE + 1, 'E-TITLE', 'TITLE: expected a title of at most '//itoa(MAX_TITLE)// &
                         ' characters, found '//itoa(len(m%title)))
         m%title = m%title(1:MAX_TITLE)
      end if
      call skip_extra(d, 'TITLE')
   end subroutine read_title

   !> Report surplus cards of a one-card block.
   subroutine skip_extra(d, card)
      type(deck_t), intent(inout) :: d
      character(len=*), intent(in) :: card
      integer :: ic
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         call d%error_at(ic, 1, 'E-EXTRA', card//': block has one card only; unexpected card "'// &
                         shown(trim(d%cards(ic)%text))//'"')
      end do
   end subroutine skip_extra

   ! ------------------------------------------------------------------ CONTROL

   subroutine read_control(d, ickw, m, ctl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(control_t), intent(inout) :: ctl
      integer :: ic
      logical :: ok
      character(len=:), allocatable :: w

      ic = next_data_card(d, 'CONTROL', 'the control card (NPOIN in columns 1-5)')
      if (ic == 0) then
         call d%error_at(ickw, 1, 'E-CONTROL', 'CONTROL: expected the control card '// &
                         '(NPOIN NELEM NVFIX NTYPE NNODE NMATS NGAUS SOLVER) after the keyword')
         return
      end if
      ctl%line = d%cards(ic)%line
      ok = .true.
      call d%get_int(ic, 1, 5, 'CONTROL', 'NPOIN', m%npoin, ok, default=0)
      call d%get_int(ic, 6, 10, 'CONTROL', 'NELEM', m%nelem, ok, default=0)
      call d%get_int(ic, 11, 15, 'CONTROL', 'NVFIX', ctl%nvfix, ok)
      call d%get_int(ic, 16, 20, 'CONTROL', 'NTYPE', m%ntype, ok)
      call d%get_int(ic, 21, 25, 'CONTROL', 'NNODE', m%nnode, ok, default=0)
      call d%get_int(ic, 26, 30, 'CONTROL', 'NMATS', m%nmats, ok)
      call d%get_int(ic, 31, 35, 'CONTROL', 'NGAUS', m%ngaus, ok, default=0)
      call d%get_word(ic, 36, 45, 'CONTROL', 'SOLVER', w, ok, default='AUTO')
      ctl%counts_from_mesh = ok .and. m%npoin == 0 .and. m%nelem == 0
      if (ok) then
         if (ctl%counts_from_mesh) then
            ! NPOIN = NELEM = 0: the mesh comes from a MESH block; NNODE 0 = any element of the file
            if (all(m%nnode /= [0, 3, 4, 8, 9])) call bad(21, 'NNODE (columns 21-25) expected 0 or blank (any '// &
                                                          'element of the mesh file), 3, 4, 8 or 9, found '//itoa(m%nnode))
         else
            if (m%npoin < 1) call bad(1, 'NPOIN (columns 1-5) expected a positive number of nodes, found '// &
                                      itoa(m%npoin))
            if (m%nelem < 1) call bad(6, 'NELEM (columns 6-10) expected a positive number of elements, found '// &
                                      itoa(m%nelem))
            if (all(m%nnode /= [3, 4, 8, 9])) call bad(21, 'NNODE (columns 21-25) expected 3, 4, 8 or 9 nodes '// &
                                                       'per element, found '//itoa(m%nnode))
         end if
         if (ctl%nvfix < 0) call bad(11, 'NVFIX (columns 11-15) expected a number of restraint cards >= 0, found '// &
                                     itoa(ctl%nvfix))
         if (m%ntype < 1 .or. m%ntype > 3) call bad(16, 'NTYPE (columns 16-20) expected 1 (plane stress), '// &
                                                    '2 (plane strain) or 3 (axisymmetric), found '//itoa(m%ntype))
         if (m%nmats < 1) call bad(26, 'NMATS (columns 26-30) expected a positive number of materials, found '// &
                                   itoa(m%nmats))
         if (m%ngaus < 0 .or. m%ngaus > 4) call bad(31, 'NGAUS (columns 31-35) expected 0 (default rule) '// &
                                                    'or 1-4 Gauss points per direction, found '//itoa(m%ngaus))
         if (m%nnode == 3 .and. all(m%ngaus /= [0, 1, 3])) call bad(31, 'NGAUS (columns 31-35) for triangles '// &
                                                                    'expected 0, 1 or 3 points, found '//itoa(m%ngaus))
         if (all(w /= [character(len=7) :: 'SKYLINE', 'UMFPACK', 'MUMPS', 'DENSE', 'AUTO'])) then
            call bad(36, 'SOLVER (columns 36-45) expected SKYLINE, UMFPACK, MUMPS, DENSE, AUTO or blank (AUTO), '// &
                     'found "'//w//'"')
         end if
      end if
      m%solver_name = w
      ctl%ok = ok
      call skip_extra(d, 'CONTROL')
   contains
      subroutine bad(col, msg)
         integer, intent(in) :: col
         character(len=*), intent(in) :: msg
         call d%error_at(ic, col, 'E-CONTROL', 'CONTROL: '//msg)
         ok = .false.
      end subroutine bad
   end subroutine read_control

   ! ------------------------------------------------------------------ OPTIONS

   subroutine read_options(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic
      logical :: ok
      real(dp) :: x
      integer :: iv
      character(len=:), allocatable :: key, val

      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         ok = .true.
         call d%get_word(ic, 1, 10, 'OPTIONS', 'KEY', key, ok)
         if (.not. ok) cycle
         select case (key)
         case ('LISTING')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'LISTING', val, ok)
            if (ok .and. all(val /= [character(len=5) :: 'FULL', 'SHORT', 'NONE'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: LISTING (columns 11-20) expected FULL, SHORT or NONE, '// &
                               'found "'//val//'"')
            else if (ok) then
               m%listing_level = val
            end if
         case ('RENUMBER')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'RENUMBER', val, ok)
            if (ok .and. all(val /= [character(len=4) :: 'RCM', 'NONE'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: RENUMBER (columns 11-20) expected RCM or NONE, '// &
                               'found "'//val//'"')
            else if (ok) then
               m%renumber = val
            end if
         case ('AUTOINC')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'AUTOINC', val, ok)
            call d%get_real(ic, 21, 30, 'OPTIONS', 'MINFRAC', x, ok, default=1.0_dp/128.0_dp)
            call d%get_int(ic, 31, 40, 'OPTIONS', 'NEASY', iv, ok, default=4)
            if (ok .and. all(val /= [character(len=3) :: 'ON', 'OFF'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: AUTOINC (columns 11-20) expected ON or OFF, '// &
                               'found "'//val//'"')
            else if (ok .and. .not. (x > 0.0_dp .and. x <= 1.0_dp)) then
               call d%error_at(ic, 21, 'E-OPTION', 'OPTIONS: AUTOINC MINFRAC (columns 21-30) expected the '// &
                               'smallest step as a fraction of a deck increment, in (0, 1], found '//rtoa(x))
            else if (ok .and. iv < 1) then
               call d%error_at(ic, 31, 'E-OPTION', 'OPTIONS: AUTOINC NEASY (columns 31-40) expected a number '// &
                               'of solutions >= 1, found '//itoa(iv))
            else if (ok) then
               m%autoinc = val == 'ON'
               m%autoinc_min = x
               m%autoinc_easy = iv
            end if
         case ('RESULTS')
            call d%get_int(ic, 11, 20, 'OPTIONS', 'RESULTS', iv, ok)
            if (ok .and. iv < 1) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: RESULTS (columns 11-20) expected the step interval '// &
                               'of the result file, an integer >= 1, found '//itoa(iv))
            else if (ok) then
               m%results_every = iv
            end if
         case ('CONDENSE')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'CONDENSE', val, ok)
            if (ok .and. all(val /= [character(len=4) :: 'AUTO', 'ON', 'OFF'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: CONDENSE (columns 11-20) expected AUTO, ON or OFF, '// &
                               'found "'//val//'"')
            else if (ok) then
               m%condense = val
            end if
         case default
            call d%error_at(ic, 1, 'E-OPTION', 'OPTIONS: unknown option "'//key//'" (columns 1-10); '// &
                            'known: LISTING, RESULTS, RENUMBER, AUTOINC, CONDENSE')
         end select
      end do
   end subroutine read_options

   ! ------------------------------------------------------------------ ELEMENTS

   subroutine read_elements(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic, ncards, ielem, imat, k, j, node(MAX_NODE), c1
      logical :: ok

      allocate (m%lnods(MAX_NODE, m%nelem), m%nnode_e(m%nelem), m%matno(m%nelem), m%elem_line(m%nelem))
      m%lnods = 0
      m%nnode_e = m%nnode
      m%matno = 0
      m%elem_line = 0
      ncards = 0
      do
         ic = next_data_card(d, 'ELEMENTS', 'an element card (element number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'ELEMENTS', 'IELEM', ielem, ok)
         call d%get_int(ic, 6, 10, 'ELEMENTS', 'MATNO', imat, ok)
         do k = 1, m%nnode
            c1 = 11 + 5*(k - 1)
            call d%get_int(ic, c1, c1 + 4, 'ELEMENTS', 'NODE'//itoa(k), node(k), ok)
         end do
         if (len_trim(d%field_text(ic, 11 + 5*m%nnode, 10000)) > 0) then
            call d%error_at(ic, 11 + 5*m%nnode, 'E-EXTRA', 'ELEMENTS: NNODE = '//itoa(m%nnode)// &
                            ' on the control card, but the card has more fields: "'// &
                            shown(trim(adjustl(d%field_text(ic, 11 + 5*m%nnode, 10000))))//'"')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (ielem < 1 .or. ielem > m%nelem) then
            call d%error_at(ic, 1, 'E-RANGE', 'ELEMENTS: element number (columns 1-5) expected 1..'// &
                            itoa(m%nelem)//' (NELEM), found '//itoa(ielem))
            cycle
         end if
         if (m%elem_line(ielem) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'ELEMENTS: element '//itoa(ielem)// &
                            ' is defined twice (first on line '//itoa(m%elem_line(ielem))//')')
            cycle
         end if
         if (imat < 1 .or. imat > m%nmats) then
            call d%error_at(ic, 6, 'E-RANGE', 'ELEMENTS: material number MATNO (columns 6-10) expected 1..'// &
                            itoa(m%nmats)//' (NMATS), found '//itoa(imat))
            ok = .false.
         end if
         do k = 1, m%nnode
            c1 = 11 + 5*(k - 1)
            if (node(k) < 1 .or. node(k) > m%npoin) then
               call d%error_at(ic, c1, 'E-RANGE', 'ELEMENTS: NODE'//itoa(k)//' (columns '//itoa(c1)//'-'// &
                               itoa(c1 + 4)//') expected a node number 1..'//itoa(m%npoin)// &
                               ' (NPOIN), found '//itoa(node(k)))
               ok = .false.
            end if
            do j = 1, k - 1
               if (node(j) == node(k)) then
                  call d%error_at(ic, c1, 'E-ELEMENT', 'ELEMENTS: node '//itoa(node(k))// &
                                  ' appears twice in element '//itoa(ielem))
                  ok = .false.
               end if
            end do
         end do
         m%elem_line(ielem) = d%cards(ic)%line
         if (.not. ok) cycle
         m%lnods(1:m%nnode, ielem) = node(1:m%nnode)
         m%matno(ielem) = imat
      end do
      if (ncards /= m%nelem) then
         call d%error_at(ickw, 1, 'E-COUNT', 'ELEMENTS: NELEM = '//itoa(m%nelem)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'ELEMENTS', 'element', m%elem_line)
      end if
   end subroutine read_elements

   !> Name the numbers 1..n that no card defined.
   subroutine report_missing(d, ickw, card, what, line_of)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      character(len=*), intent(in) :: card, what
      integer, intent(in) :: line_of(:)
      integer :: i, nmiss
      character(len=:), allocatable :: list
      nmiss = 0
      list = ''
      do i = 1, size(line_of)
         if (line_of(i) == 0) then
            nmiss = nmiss + 1
            if (nmiss <= 10) list = list//' '//itoa(i)
         end if
      end do
      if (nmiss > 10) list = list//' ...'
      if (nmiss > 0) call d%error_at(ickw, 1, 'E-MISSING', card//': no card defines '//what//'(s)'//list)
   end subroutine report_missing

   ! ------------------------------------------------------------------ NODES

   subroutine read_nodes(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic, ncards, ipoin
      real(dp) :: x, y
      logical :: ok

      allocate (m%coord(2, m%npoin), m%node_line(m%npoin))
      m%coord = 0.0_dp
      m%node_line = 0
      ncards = 0
      do
         ic = next_data_card(d, 'NODES', 'a node card (node number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'NODES', 'IPOIN', ipoin, ok)
         call d%get_real(ic, 6, 15, 'NODES', 'X', x, ok)
         call d%get_real(ic, 16, 25, 'NODES', 'Y', y, ok)
         call d%check_coordinate(ic, 6, 'NODES', 'X', x, ok)
         call d%check_coordinate(ic, 16, 'NODES', 'Y', y, ok)
         if (len_trim(d%field_text(ic, 26, 10000)) > 0) then
            call d%error_at(ic, 26, 'E-EXTRA', 'NODES: expected IPOIN, X, Y in columns 1-25, found more: "'// &
                            shown(trim(adjustl(d%field_text(ic, 26, 10000))))//'"')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (ipoin < 1 .or. ipoin > m%npoin) then
            call d%error_at(ic, 1, 'E-RANGE', 'NODES: node number (columns 1-5) expected 1..'// &
                            itoa(m%npoin)//' (NPOIN), found '//itoa(ipoin))
            cycle
         end if
         if (m%node_line(ipoin) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'NODES: node '//itoa(ipoin)// &
                            ' is defined twice (first on line '//itoa(m%node_line(ipoin))//')')
            cycle
         end if
         if (m%ntype == NTYPE_AXISYMMETRIC .and. x < 0.0_dp) then
            call d%error_at(ic, 6, 'E-RANGE', 'NODES: axisymmetric analysis needs radius X >= 0 (columns 6-15), found '// &
                            rtoa(x))
         end if
         m%node_line(ipoin) = d%cards(ic)%line
         m%coord(:, ipoin) = [x, y]
      end do
      if (ncards /= m%npoin) then
         call d%error_at(ickw, 1, 'E-COUNT', 'NODES: NPOIN = '//itoa(m%npoin)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'NODES', 'node', m%node_line)
      end if
   end subroutine read_nodes

   ! ------------------------------------------------------------------ RESTRAINTS

   subroutine read_restraints(d, ickw, m, ctl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(control_t), intent(in) :: ctl
      type(restraint_t), allocatable :: list(:)
      integer, allocatable :: first_line(:)
      integer :: ic, n, node, code, icase, ngroup, ngroup_entries, k0
      real(dp) :: ux, uy
      logical :: ok

      ngroup = 0        ! GROUP cards, and the restraint entries they gave
      ngroup_entries = 0
      allocate (list(max(ctl%nvfix, 0) + 16), first_line(m%npoin))
      first_line = 0
      n = 0
      do
         ic = next_data_card(d, 'RESTRAINTS', 'a restraint card (node number in columns 1-5)', allow_group=.true.)
         if (ic == 0) exit
         if (is_group_card(d, ic)) then
            ngroup = ngroup + 1
            k0 = n
            call read_group_restraint(d, ic, m, list, n)
            ngroup_entries = ngroup_entries + (n - k0)
            cycle
         end if
         ok = .true.
         call d%get_int(ic, 1, 5, 'RESTRAINTS', 'NODE', node, ok)
         call d%get_int(ic, 6, 10, 'RESTRAINTS', 'CODE', code, ok)
         call d%get_real(ic, 11, 20, 'RESTRAINTS', 'UX', ux, ok, default=0.0_dp)
         call d%get_real(ic, 21, 30, 'RESTRAINTS', 'UY', uy, ok, default=0.0_dp)
         call d%get_int(ic, 31, 35, 'RESTRAINTS', 'CASE', icase, ok, default=1)
         call check_tail(d, ic, 36, 'RESTRAINTS', 'NODE, CODE, UX, UY, CASE in columns 1-35', ok)
         call d%check_magnitude(ic, 11, 'RESTRAINTS', 'UX', ux, ok)
         call d%check_magnitude(ic, 21, 'RESTRAINTS', 'UY', uy, ok)
         if (n >= size(list)) list = [list, list]
         n = n + 1
         list(n) = restraint_t()
         if (.not. ok) cycle
         if (node < 1 .or. node > m%npoin) then
            call d%error_at(ic, 1, 'E-RANGE', 'RESTRAINTS: NODE (columns 1-5) expected a node number 1..'// &
                            itoa(m%npoin)//', found '//itoa(node))
            cycle
         end if
         if (all(code /= [1, 10, 11])) then
            call d%error_at(ic, 6, 'E-CODE', 'RESTRAINTS: CODE (columns 6-10) expected 10 (x fixed), '// &
                            '01 (y fixed) or 11 (both), found '//itoa(code))
            cycle
         end if
         if (icase < 1 .or. icase > MAX_CASE) then
            call d%error_at(ic, 31, 'E-RANGE', 'RESTRAINTS: CASE (columns 31-35) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                            itoa(icase))
            cycle
         end if
         if (first_line(node) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'RESTRAINTS: node '//itoa(node)// &
                            ' is restrained twice (first on line '//itoa(first_line(node))//'); give one card with CODE 11')
            cycle
         end if
         first_line(node) = d%cards(ic)%line
         list(n)%node = node
         list(n)%fixed = [code >= 10, mod(code, 10) == 1]
         list(n)%value = [ux, uy]
         if (.not. list(n)%fixed(1) .and. abs(ux) > 0.0_dp) call d%error_at(ic, 11, 'E-CODE', &
                             'RESTRAINTS: UX = '//rtoa(ux)//' is prescribed but CODE '//itoa(code)//' leaves x free')
         if (.not. list(n)%fixed(2) .and. abs(uy) > 0.0_dp) call d%error_at(ic, 21, 'E-CODE', &
                             'RESTRAINTS: UY = '//rtoa(uy)//' is prescribed but CODE '//itoa(code)//' leaves y free')
         list(n)%icase = icase
         list(n)%line = d%cards(ic)%line
      end do
      if (n - ngroup_entries + ngroup /= ctl%nvfix) then
         call d%error_at(ickw, 1, 'E-COUNT', 'RESTRAINTS: NVFIX = '//itoa(ctl%nvfix)// &
                         ' on the control card, but the block has '//itoa(n - ngroup_entries + ngroup)//' cards')
      end if
      m%fixes = pack(list(1:n), list(1:n)%node > 0)
      if (ngroup > 0) call check_restraint_overlaps(d, m, m%fixes)
   end subroutine read_restraints

   !> Anything past the last field of a card is an error.
   subroutine check_tail(d, ic, col, card, expected, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, col
      character(len=*), intent(in) :: card, expected
      logical, intent(inout) :: ok
      character(len=:), allocatable :: tail
      tail = trim(adjustl(d%field_text(ic, col, 100000)))
      if (len(tail) > 0) then
         call d%error_at(ic, col, 'E-EXTRA', card//': expected '//expected//', found more: "'//shown(tail)//'"')
         ok = .false.
      end if
   end subroutine check_tail

   ! ------------------------------------------------------------------ MATERIALS

   subroutine read_materials(d, ickw, m, warnings)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: warnings
      integer :: ic, ncards, imat
      integer, allocatable :: line_of(:)
      real(dp) :: e, nu, t
      logical :: ok

      if (allocated(m%mats)) deallocate (m%mats)
      allocate (m%mats(m%nmats), line_of(m%nmats))
      line_of = 0
      ncards = 0
      do
         ic = next_data_card(d, 'MATERIALS', 'a material card (material number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'MATERIALS', 'MATNO', imat, ok)
         call d%get_real(ic, 6, 15, 'MATERIALS', 'E', e, ok)
         call d%get_real(ic, 16, 25, 'MATERIALS', 'NU', nu, ok)
         call d%get_real(ic, 26, 35, 'MATERIALS', 'THICK', t, ok, default=1.0_dp)
         call check_tail(d, ic, 36, 'MATERIALS', 'MATNO, E, NU, THICK in columns 1-35', ok)
         if (.not. ok) cycle
         if (imat < 1 .or. imat > m%nmats) then
            call d%error_at(ic, 1, 'E-RANGE', 'MATERIALS: MATNO (columns 1-5) expected 1..'//itoa(m%nmats)// &
                            ' (NMATS), found '//itoa(imat))
            cycle
         end if
         if (line_of(imat) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'MATERIALS: material '//itoa(imat)// &
                            ' is defined twice (first on line '//itoa(line_of(imat))//')')
            cycle
         end if
         line_of(imat) = d%cards(ic)%line
         if (.not. (e > 0.0_dp)) call d%error_at(ic, 6, 'E-MATERIAL', 'MATERIALS: E (columns 6-15) expected '// &
                                                 'a positive Young''s modulus, found '//rtoa(e))
         if (.not. (nu > -1.0_dp .and. nu < 0.5_dp)) call d%error_at(ic, 16, 'E-MATERIAL', &
                                  'MATERIALS: NU (columns 16-25) expected Poisson''s ratio in (-1, 0.5), found '//rtoa(nu))
         if (.not. (t > 0.0_dp)) call d%error_at(ic, 26, 'E-MATERIAL', 'MATERIALS: THICK (columns 26-35) expected '// &
                                                 'a positive thickness, found '//rtoa(t))
         if (m%ntype == NTYPE_AXISYMMETRIC .and. len_trim(d%field_text(ic, 26, 35)) > 0 .and. abs(t - 1.0_dp) > 0.0_dp) then
            call warnings%add('W-THICK', 'MATERIALS: THICK is ignored in axisymmetric analysis (the ring '// &
                              'weight 2*pi*r is used)', file=d%file, line=d%cards(ic)%line, col=26)
         end if
         if (e > 0.0_dp .and. nu > -1.0_dp .and. nu < 0.5_dp .and. t > 0.0_dp) then
            if (.not. stiffness_fits(e, nu, t)) call d%error_at(ic, 6, 'E-MATERIAL', 'MATERIALS: E = '//rtoa(e)// &
                ', NU = '//rtoa(nu)//' and THICK = '//rtoa(t)//' give elastic constants beyond '// &
                rtoa(sqrt(huge(1.0_dp)))//' or below '//rtoa(1.0_dp/sqrt(huge(1.0_dp)))// &
                ' (the analysis multiplies loads by compliances and displacements by stiffnesses): out of range')
         end if
         m%mats(imat) = material_t(young=e, poiss=nu, thick=t, line=d%cards(ic)%line)
      end do
      if (ncards /= m%nmats) then
         call d%error_at(ickw, 1, 'E-COUNT', 'MATERIALS: NMATS = '//itoa(m%nmats)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'MATERIALS', 'material', line_of)
      end if
   end subroutine read_materials

   !> Whether the constants of the elasticity matrix D (MODPS: E/(1-nu^2),
   !! E(1-nu)/((1+nu)(1-2nu)), its nu/(1-nu) multiple, G = E/(2(1+nu))),
   !! times the thickness, stay within [1/sqrt(huge), sqrt(huge)]: the analysis
   !! multiplies displacements by stiffnesses (K u, the Schur complement
   !! K_cb K_bb^-1 K_bc) and loads by compliances (u = K^-1 f), and loads and
   !! prescribed displacements are bounded by sqrt(huge) (check_magnitude), so
   !! that every such product stays representable.  Evaluated on logarithms,
   !! so that the check itself cannot overflow.
   !! Ref: Hinton & Owen, *Finite Element Programming*, routine MODPS.
   pure logical function stiffness_fits(e, nu, t)
      real(dp), intent(in) :: e      !! Young's modulus [stress], > 0
      real(dp), intent(in) :: nu     !! Poisson's ratio, in (-1, 0.5)
      real(dp), intent(in) :: t      !! thickness [length], > 0
      real(dp) :: lmax, lmin
      lmax = log(e) + log(max(t, 1.0_dp)) + max(-log(1.0_dp - nu*nu), &
             log(1.0_dp - nu) - log(1.0_dp + nu) - log(1.0_dp - 2.0_dp*nu), &
             log(max(abs(nu), tiny(1.0_dp))) - log(1.0_dp + nu) - log(1.0_dp - 2.0_dp*nu), &
             -log(2.0_dp*(1.0_dp + nu)))
      ! the diagonal constants are at least G = E/(2(1+nu)) > E/3
      lmin = log(e) + log(min(t, 1.0_dp)) - log(3.0_dp)
      stiffness_fits = lmax < 0.5_dp*log(huge(1.0_dp)) .and. lmin > -0.5_dp*log(huge(1.0_dp))
   end function stiffness_fits

   ! ------------------------------------------------------------------ LOADS

   subroutine read_loads(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic
      character(len=:), allocatable :: sub
      type(point_load_t), allocatable :: pl(:)
      type(edge_load_t), allocatable :: el(:)
      type(body_load_t), allocatable :: bl(:)
      integer :: npl, nel, nbl
      type(pretension_t), allocatable :: pts(:)

      allocate (pl(16), el(16), bl(4), pts(0))
      npl = 0
      nel = 0
      nbl = 0
      sub = ''
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         if (is_group_card(d, ic) .and. (sub == 'POINT' .or. sub == 'EDGE')) then
            if (sub == 'POINT') call read_group_point_load(d, ic, m, pl, npl)
            if (sub == 'EDGE') call read_group_edge_load(d, ic, m, el, nel)
            cycle
         end if
         if (sub == 'PRETENSION' .and. is_pretension_card(d, ic)) then
            call read_pretension_card(d, ic, m, pts)
            cycle
         end if
         if (d%is_keyword_card(ic)) then
            sub = d%keyword(ic)
            if (all(sub /= [character(len=10) :: 'POINT', 'EDGE', 'BODY', 'PRETENSION'])) then
               call d%error_at(ic, 1, 'E-CARD', 'LOADS: expected a sub-block keyword POINT, EDGE, BODY or PRETENSION, '// &
                               'or a load card, found "'//shown(trim(d%cards(ic)%text))//'"')
               sub = 'BAD'
            end if
            cycle
         end if
         select case (sub)
         case ('POINT')
            if (npl >= size(pl)) pl = [pl, pl]
            npl = npl + 1
            call read_point_load(d, ic, m, pl(npl))
         case ('EDGE')
            if (.not. allocated(m%nnode_e)) then
               ! the card names an element, and no element was read
               call d%error_at(ic, 1, 'E-CARD', 'LOADS/EDGE: an edge load refers to element numbers, but no '// &
                               'elements were read (the ELEMENTS block is missing or was rejected)')
               sub = 'BAD'
               cycle
            end if
            if (nel >= size(el)) el = [el, el]
            nel = nel + 1
            call read_edge_load(d, ic, m, el(nel))
         case ('PRETENSION')
            if (size(pts) == 0) then
               call d%error_at(ic, 1, 'E-CARD', 'LOADS/PRETENSION: expected a GROUP or SECTION card, found "'// &
                               shown(trim(d%cards(ic)%text))//'"')
               sub = 'BAD'
            else if (pts(size(pts))%group) then
               if (pts(size(pts))%line > 0) call d%error_at(ic, 1, 'E-CARD', 'LOADS/PRETENSION: node numbers '// &
                  'follow a SECTION card only (a GROUP takes the nodes of its set), found "'// &
                  shown(trim(d%cards(ic)%text))//'"')
            else
               call read_pretension_nodes(d, ic, m, pts(size(pts)))
            end if
         case ('BODY')
            if (nbl >= size(bl)) bl = [bl, bl]
            nbl = nbl + 1
            call read_body_load(d, ic, m, bl(nbl))
         case ('')
            call d%error_at(ic, 1, 'E-CARD', 'LOADS: a load card must follow a sub-block keyword '// &
                            'POINT, EDGE or BODY, found "'//shown(trim(d%cards(ic)%text))//'"')
            sub = 'BAD'
         case default
            continue   ! cards under a bad sub-block keyword were already reported
         end select
      end do
      m%point_loads = pack(pl(1:npl), pl(1:npl)%node > 0)
      m%edge_loads = pack(el(1:nel), el(1:nel)%ielem > 0)
      m%body_loads = pack(bl(1:nbl), bl(1:nbl)%line > 0)
      call finish_pretensions(d, pts, m)
   end subroutine read_loads

   subroutine read_point_load(d, ic, m, p)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(point_load_t), intent(out) :: p
      integer :: node, icase
      real(dp) :: fx, fy
      logical :: ok
      ok = .true.
      call d%get_int(ic, 1, 5, 'LOADS/POINT', 'NODE', node, ok)
      call d%get_real(ic, 6, 15, 'LOADS/POINT', 'FX', fx, ok, default=0.0_dp)
      call d%get_real(ic, 16, 25, 'LOADS/POINT', 'FY', fy, ok, default=0.0_dp)
      call d%get_int(ic, 26, 30, 'LOADS/POINT', 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 31, 'LOADS/POINT', 'NODE, FX, FY, CASE in columns 1-30', ok)
      call d%check_magnitude(ic, 6, 'LOADS/POINT', 'FX', fx, ok)
      call d%check_magnitude(ic, 16, 'LOADS/POINT', 'FY', fy, ok)
      if (.not. ok) return
      if (node < 1 .or. node > m%npoin) then
         call d%error_at(ic, 1, 'E-RANGE', 'LOADS/POINT: NODE (columns 1-5) expected a node number 1..'// &
                         itoa(m%npoin)//', found '//itoa(node))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 26, 'E-RANGE', 'LOADS/POINT: CASE (columns 26-30) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         return
      end if
      p = point_load_t(node=node, force=[fx, fy], icase=icase, line=d%cards(ic)%line)
   end subroutine read_point_load

   subroutine read_edge_load(d, ic, m, e)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(edge_load_t), intent(out) :: e
      integer :: ielem, nd(3), icase, nn, k, iedge, loc(3), nloc, nnode, a, b, mid
      real(dp) :: pn(3), pt(3)
      logical :: ok, found
      character(len=*), parameter :: card = 'LOADS/EDGE'

      ok = .true.
      call d%get_int(ic, 1, 5, card, 'IELEM', ielem, ok)
      call d%get_int(ic, 6, 10, card, 'N1', nd(1), ok)
      call d%get_int(ic, 11, 15, card, 'N2', nd(2), ok)
      call d%get_int(ic, 16, 20, card, 'N3', nd(3), ok, default=0)
      do k = 1, 3
         call d%get_real(ic, 11 + 10*k, 20 + 10*k, card, 'PN'//itoa(k), pn(k), ok, default=0.0_dp)
      end do
      do k = 1, 3
         call d%get_real(ic, 41 + 10*k, 50 + 10*k, card, 'PT'//itoa(k), pt(k), ok, default=0.0_dp)
      end do
      call d%get_int(ic, 81, 85, card, 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 86, card, 'IELEM, N1-N3, PN1-PN3, PT1-PT3, CASE in columns 1-85', ok)
      do k = 1, 3
         call d%check_magnitude(ic, 11 + 10*k, card, 'PN'//itoa(k), pn(k), ok)
         call d%check_magnitude(ic, 41 + 10*k, card, 'PT'//itoa(k), pt(k), ok)
      end do
      if (.not. ok) return
      if (ielem < 1 .or. ielem > m%nelem) then
         call d%error_at(ic, 1, 'E-RANGE', card//': IELEM (columns 1-5) expected an element number 1..'// &
                         itoa(m%nelem)//', found '//itoa(ielem))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 81, 'E-RANGE', card//': CASE (columns 81-85) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         return
      end if
      nnode = m%nnode_e(ielem)
      nn = merge(3, 2, nd(3) /= 0)
      if (nnode >= 8 .and. nn == 2) then
         call d%error_at(ic, 16, 'E-EDGE', card//': element '//itoa(ielem)//' has quadratic edges: expected '// &
                         'N1 (corner), N2 (midside), N3 (corner), found only two nodes')
         return
      end if
      if (nnode < 8 .and. nn == 3) then
         call d%error_at(ic, 16, 'E-EDGE', card//': element '//itoa(ielem)//' has straight 2-node edges: '// &
                         'expected N1, N2 and a blank N3, found N3 = '//itoa(nd(3)))
         return
      end if
      if (any(m%lnods(1:nnode, ielem) == 0)) return   ! element card was bad, already reported
      ! corner nodes given by the user: first and last; midside: N2 of a quadratic edge
      a = nd(1)
      b = nd(nn)
      mid = 0
      if (nn == 3) mid = nd(2)
      found = .false.
      do iedge = 1, nedges(nnode)
         call element_edge_nodes(nnode, iedge, loc, nloc)
         associate (ga => m%lnods(loc(1), ielem), gb => m%lnods(loc(2), ielem))
            if (nn == 3) then
               if (m%lnods(loc(3), ielem) /= mid) cycle
            end if
            if (ga == a .and. gb == b) then
               found = .true.
               e%nodes(1:2) = [a, b]
               e%pn(1:2) = [pn(1), pn(nn)]
               e%pt(1:2) = [pt(1), pt(nn)]
            else if (ga == b .and. gb == a) then
               ! listed against the element's anticlockwise order: the user's
               ! tangential direction (first to last node) is reversed
               found = .true.
               e%nodes(1:2) = [b, a]
               e%pn(1:2) = [pn(nn), pn(1)]
               e%pt(1:2) = -[pt(nn), pt(1)]
            end if
         end associate
         if (found) exit
      end do
      if (.not. found) then
         if (nn == 3) then
            call d%error_at(ic, 6, 'E-EDGE', card//': nodes '//itoa(nd(1))//' '//itoa(nd(2))//' '//itoa(nd(3))// &
                            ' do not form an edge of element '//itoa(ielem)// &
                            ' (expected corner, midside, corner along one side)')
         else
            call d%error_at(ic, 6, 'E-EDGE', card//': nodes '//itoa(nd(1))//' '//itoa(nd(2))// &
                            ' do not form an edge of element '//itoa(ielem)//' (expected the two corners of one side)')
         end if
         return
      end if
      if (nn == 3) then
         e%nodes(3) = mid
         e%pn(3) = pn(2)
         e%pt(3) = merge(pt(2), -pt(2), e%nodes(1) == a)
      end if
      e%ielem = ielem
      e%nn = nn
      e%icase = icase
      e%line = d%cards(ic)%line
   end subroutine read_edge_load

   subroutine read_body_load(d, ic, m, bl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(model_t), intent(in) :: m
      type(body_load_t), intent(out) :: bl
      integer :: imat, icase
      real(dp) :: bx, by
      logical :: ok
      ok = .true.
      call d%get_int(ic, 1, 5, 'LOADS/BODY', 'MATNO', imat, ok, default=0)
      call d%get_real(ic, 6, 15, 'LOADS/BODY', 'BX', bx, ok, default=0.0_dp)
      call d%get_real(ic, 16, 25, 'LOADS/BODY', 'BY', by, ok, default=0.0_dp)
      call d%get_int(ic, 26, 30, 'LOADS/BODY', 'CASE', icase, ok, default=1)
      call check_tail(d, ic, 31, 'LOADS/BODY', 'MATNO, BX, BY, CASE in columns 1-30', ok)
      call d%check_magnitude(ic, 6, 'LOADS/BODY', 'BX', bx, ok)
      call d%check_magnitude(ic, 16, 'LOADS/BODY', 'BY', by, ok)
      if (.not. ok) return
      if (imat < 0 .or. imat > m%nmats) then
         call d%error_at(ic, 1, 'E-RANGE', 'LOADS/BODY: MATNO (columns 1-5) expected 0 (all) or 1..'// &
                         itoa(m%nmats)//', found '//itoa(imat))
         return
      end if
      if (icase < 1 .or. icase > MAX_CASE) then
         call d%error_at(ic, 26, 'E-RANGE', 'LOADS/BODY: CASE (columns 26-30) expected a load case '// &
                         '1..'//itoa(MAX_CASE)//', found '// &
                         itoa(icase))
         return
      end if
      bl = body_load_t(imat=imat, b=[bx, by], icase=icase, line=d%cards(ic)%line)
   end subroutine read_body_load

   ! ------------------------------------------------------------------ INCREMENTS

   !> Load history: each card (NSTEP, LAMBDA_1 .. LAMBDA_ncase) ramps the total
   !! factor of every load case linearly to its target in NSTEP equal
   !! increments; a blank target holds the previous value.
   subroutine read_increments(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic, nstep, ncase, k, c1, i, nincs
      real(dp), allocatable :: target(:), prev(:), lam(:, :)
      real(dp) :: val
      logical :: ok

      ncase = max(1, maxval([1, m%fixes%icase, m%point_loads%icase, m%edge_loads%icase, m%body_loads%icase]))
      if (allocated(m%pretensions)) ncase = max(ncase, maxval([1, m%pretensions%icase]))
      m%ncase = ncase
      allocate (target(ncase), prev(ncase), lam(ncase, 0:64))
      lam = 0.0_dp
      prev = 0.0_dp
      nincs = 0
      do
         ic = next_data_card(d, 'INCREMENTS', 'an increment card (NSTEP in columns 1-5)')
         if (ic == 0) exit
         ok = .true.
         call d%get_int(ic, 1, 5, 'INCREMENTS', 'NSTEP', nstep, ok)
         target = prev
         do k = 1, ncase
            c1 = 6 + 10*(k - 1)
            call d%get_real(ic, c1, c1 + 9, 'INCREMENTS', 'LAMBDA'//itoa(k), val, ok, default=prev(k))
            ! the ramp from the previous factor takes differences: bounded so that they cannot overflow
            if (ok .and. abs(val) > 0.25_dp*huge(val)) then
               call d%error_at(ic, c1, 'E-RANGE', 'INCREMENTS: LAMBDA'//itoa(k)//' (columns '//itoa(c1)//'-'// &
                               itoa(c1 + 9)//') expected a load factor of magnitude at most '// &
                               rtoa(0.25_dp*huge(val))//', found '//rtoa(val))
               ok = .false.
            end if
            target(k) = val
         end do
         call check_tail(d, ic, 6 + 10*ncase, 'INCREMENTS', 'NSTEP and '//itoa(ncase)// &
                         ' load factor(s), one per load case used by the deck', ok)
         if (.not. ok) cycle
         if (nstep < 1 .or. nstep > 100000) then
            call d%error_at(ic, 1, 'E-RANGE', 'INCREMENTS: NSTEP (columns 1-5) expected 1..100000 increments, found '// &
                            itoa(nstep))
            cycle
         end if
         if (nincs + nstep > ubound(lam, 2)) call grow(lam, nincs + nstep)
         do i = 1, nstep
            lam(:, nincs + i) = prev + (target - prev)*(real(i, dp)/real(nstep, dp))
         end do
         nincs = nincs + nstep
         prev = target
      end do
      if (nincs == 0) then
         call d%error_eof('E-INCREMENTS', 'INCREMENTS: the block has no increment cards; omit the block '// &
                          'for a single increment to load factor 1')
         return
      end if
      m%nincs = nincs
      allocate (m%lambda(ncase, 0:nincs))
      m%lambda = lam(:, 0:nincs)
   contains
      subroutine grow(a, nmin)
         real(dp), allocatable, intent(inout) :: a(:, :)
         integer, intent(in) :: nmin
         real(dp), allocatable :: t(:, :)
         allocate (t(size(a, 1), 0:max(nmin, 2*ubound(a, 2))))
         t = 0.0_dp
         t(:, 0:ubound(a, 2)) = a
         call move_alloc(t, a)
      end subroutine grow
   end subroutine read_increments

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
      m%ncase = max(1, maxval([1, m%fixes%icase, m%point_loads%icase, m%edge_loads%icase, m%body_loads%icase, &
                               m%pretensions%icase]))
      if (m%nincs == 0) then
         m%nincs = 1
         allocate (m%lambda(m%ncase, 0:1))
         m%lambda(:, 0) = 0.0_dp
         m%lambda(:, 1) = 1.0_dp
      end if
   end subroutine finish_model

end module deck_reader
