!> Readers of the TIES and CONTACT blocks of a deck (docs/deck-format.md).
!!
!! CONTACT holds keyword cards (keyword in columns 1-10, values in fields of
!! ten columns from column 11) and, after SURFACE, PAIRS and RIGID POLYLINE
!! cards, data cards of node numbers, pairs or vertices.  One reader routine
!! per card (CalculiX style), dispatched from `read_contact`'s loop; each
!! checks its own fields and stores what the card says in the model's contact
!! specification (model/contact_spec), constants in the deck's units.  Nothing
!! is built here: the pairs, areas and unit conversions come after reading
!! (contact/contact_definition, called by driver/model_input), reported at
!! the same deck lines.  A new card is a new `read_<card>` routine and one
!! line in `read_contact_keyword`.
module deck_contact
   use kinds, only: dp
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, node_set_t
   use contact_spec, only: contact_spec_t, iface_spec_t, pair_spec_t
   use deck_contact_fields, only: contact_cursor_t, DATA_NONE, DATA_SURFACE, DATA_PAIRS, &
                                  DATA_VERTICES
   use deck_contact_law, only: read_law, read_units, read_normal, read_tangent, read_friction, &
                               read_hardening, read_slip, read_tolerance
   use deck_contact_geometry, only: read_surface, read_node_list, read_pair, read_matching, &
                                    read_rigid, read_vertex
   use deck_contact_options, only: read_augmented, read_update, read_converge, read_firstinc, &
                                   read_newclosed, read_repeats, read_start
   ! TIES has its own module; read_ties is passed on so that the deck reader finds both here
   use deck_ties, only: read_ties
   implicit none
   private
   public :: read_ties, read_contact

contains

   ! ------------------------------------------------------------------ CONTACT

   !> CONTACT block: store every card in the model's contact specification
   !! (`m%contact_spec`); it is complete when the block gave an interface and
   !! raised no error.
   subroutine read_contact(d, ickw, m, is_block_card)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw            !! the CONTACT keyword card
      type(model_t), intent(inout) :: m      !! npoin used; contact_spec filled
      interface
         logical function is_block_card(d, ic)
            import :: deck_t
            type(deck_t), intent(in) :: d
            integer, intent(in) :: ic
         end function is_block_card
      end interface
      type(contact_cursor_t) :: cur
      integer :: ic, nerr0

      nerr0 = d%errors%n
      associate (cs => m%contact_spec)
         cs%given = .true.
         cs%complete = .false.
         cs%line = d%cards(ickw)%line
         allocate (cs%ifaces(0), cs%rigids(0))
         do while (.not. d%at_end())
            if (is_block_card(d, d%peek())) exit
            ic = d%next()
            if (d%is_keyword_card(ic)) then
               call read_contact_keyword(d, ic, m%npoin, m%node_sets, cs, cur)
               if (cur%mode /= DATA_NONE) call read_data_run(d, m%npoin, cs, cur)
            else
               call read_contact_data(d, ic, m%npoin, cs, cur)
            end if
         end do
         ! the interfaces grew by doubling: cut to those opened
         if (cur%nif < size(cs%ifaces)) cs%ifaces = cs%ifaces(1:cur%nif)
         if (size(cs%ifaces) == 0) then
            call d%error_at(ickw, 1, 'E-CONTACT', &
               'CONTACT: the block defines no interface (expected at least NORMAL, FRICTION '// &
               'and SURFACE or PAIRS cards)')
            return
         end if
         cs%complete = d%errors%n == nerr0
      end associate
   end subroutine read_contact

   !> A keyword card of CONTACT: open an interface where the card belongs to
   !! one, then the card's own reader.
   subroutine read_contact_keyword(d, ic, npoin, sets, cs, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(node_set_t), allocatable, &
         intent(in) :: sets(:)   !! named node sets (MESH block), for RIGID's NREF
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(inout) :: cur
      character(len=*), parameter :: iface_cards(12) = [character(len=10) :: 'LAW', 'UNITS', &
         'NORMAL', &
                                     'TANGENT', 'FRICTION', 'HARDENING', 'SLIP', 'TOLERANCE', &
                                        'SURFACE', &
                                     'PAIRS', 'MATCHING', 'RIGID']
      character(len=:), allocatable :: key
      logical :: ok
      integer :: nif

      ok = .true.
      call d%get_word(ic, 1, 10, 'CONTACT', 'KEYWORD', key, ok)
      cur%mode = DATA_NONE
      ! cards of an interface before the first INTERFACE card open interface 1
      if (key == 'INTERFACE' .or. (cur%nif == 0 .and. any(key == iface_cards))) then
         call new_interface(cs, cur, d%cards(ic)%line)
      end if
      nif = cur%nif
      select case (key)
      case ('INTERFACE')
         continue   ! opened above
      case ('LAW')
         call read_law(d, ic, cs%ifaces(nif)%law)
      case ('UNITS')
         call read_units(d, ic, cs%ifaces(nif)%law)
      case ('NORMAL')
         call read_normal(d, ic, cs%ifaces(nif))
      case ('TANGENT')
         call read_tangent(d, ic, cs%ifaces(nif)%law)
      case ('FRICTION')
         call read_friction(d, ic, cs%ifaces(nif))
      case ('HARDENING')
         call read_hardening(d, ic, cs%ifaces(nif)%law)
      case ('SLIP')
         call read_slip(d, ic, cs%ifaces(nif)%law)
      case ('TOLERANCE')
         call read_tolerance(d, ic, cs%ifaces(nif)%law)
      case ('SURFACE')
         call read_surface(d, ic, cs%ifaces(nif), cur)
      case ('PAIRS')
         cur%mode = DATA_PAIRS
      case ('MATCHING')
         call read_matching(d, ic, cs%ifaces(nif))
      case ('RIGID')
         call read_rigid(d, ic, npoin, sets, cs, cur)
      case ('AUGMENTED')
         call read_augmented(d, ic, cs%opts)
      case ('UPDATE', 'SCHEME')
         call read_update(d, ic, key, cs%opts)
      case ('CONVERGE')
         call read_converge(d, ic, cs%opts)
      case ('FIRSTINC')
         call read_firstinc(d, ic, cs%opts)
      case ('NEWCLOSED')
         call read_newclosed(d, ic, cs%opts)
      case ('REPEATS')
         call read_repeats(d, ic, cs%opts)
      case ('START')
         call read_start(d, ic, cs%opts)
      case default
         call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT: unknown keyword "'//key// &
            '" (expected INTERFACE, LAW, UNITS, NORMAL, TANGENT, FRICTION, HARDENING, SLIP, '// &
            'SURFACE, PAIRS, MATCHING, RIGID, TOLERANCE, SCHEME, UPDATE, CONVERGE, FIRSTINC, '// &
            'NEWCLOSED, REPEATS, START or AUGMENTED)')
      end select
   end subroutine read_contact_keyword

   !> The data cards after a SURFACE, PAIRS or RIGID POLYLINE card, up to the
   !! next keyword card, in two passes: count them, then read them into
   !! buffers sized once and append those at once, so that a long list costs
   !! linear time.  A node listed twice in one surface is an error.
   subroutine read_data_run(d, npoin, cs, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: npoin                  !! nodes of the model
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(in) :: cur     !! the data the cards hold
      integer :: ncard, k, ic, nn, nv, np, n0, nif
      integer, allocatable :: nodes(:), first_line(:)
      real(dp), allocatable :: xy(:, :), tmp(:, :)
      type(pair_spec_t), allocatable :: pairs(:)
      type(pair_spec_t) :: p
      logical :: ok

      ncard = 0
      do while (d%pos + ncard < d%ncard)
         if (d%is_keyword_card(d%pos + ncard + 1)) exit
         ncard = ncard + 1
      end do
      if (ncard == 0) return
      nif = cur%nif
      select case (cur%mode)
      case (DATA_SURFACE)
         associate (surf => cs%ifaces(nif)%surf(cur%iside))
            allocate (nodes(16*ncard), first_line(max(npoin, 1)))
            first_line = 0
            do k = 1, size(surf%nodes)
               if (surf%nodes(k) >= 1 .and. surf%nodes(k) <= npoin) then
                  first_line(surf%nodes(k)) = surf%line
               end if
            end do
            nn = 0
            do k = 1, ncard
               ic = d%next()
               call read_node_list(d, ic, npoin, nodes, nn, first_line)
            end do
            surf%nodes = [surf%nodes, nodes(1:nn)]
         end associate
      case (DATA_PAIRS)
         allocate (pairs(ncard))
         np = 0
         do k = 1, ncard
            ic = d%next()
            call read_pair(d, ic, npoin, p, ok)
            if (.not. ok) cycle
            np = np + 1
            pairs(np) = p
         end do
         cs%ifaces(nif)%pairs = [cs%ifaces(nif)%pairs, pairs(1:np)]
      case (DATA_VERTICES)
         allocate (xy(2, ncard))
         nv = 0
         do k = 1, ncard
            ic = d%next()
            call read_vertex(d, ic, xy(:, nv + 1), ok)
            if (ok) nv = nv + 1
         end do
         associate (rb => cs%rigids(size(cs%rigids)))
            n0 = size(rb%xy, 2)
            allocate (tmp(2, n0 + nv))
            tmp(:, 1:n0) = rb%xy
            tmp(:, n0 + 1:n0 + nv) = xy(:, 1:nv)
            call move_alloc(tmp, rb%xy)
         end associate
      end select
   end subroutine read_data_run

   !> A data card of CONTACT: what it holds depends on the last keyword card.
   subroutine read_contact_data(d, ic, npoin, cs, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(contact_spec_t), intent(in) :: cs
      type(contact_cursor_t), intent(in) :: cur
      ! the data cards of SURFACE, PAIRS and RIGID POLYLINE are read by read_data_run
      if (cur%mode /= DATA_NONE .or. npoin < 0 .or. size(cs%rigids) < 0) return
      call d%error_at(ic, 1, 'E-CARD', &
         'CONTACT: a data card must follow a SURFACE, PAIRS or RIGID POLYLINE card, found "'// &
         shown(trim(d%cards(ic)%text))//'"')
   end subroutine read_contact_data

   !> INTERFACE card (or the first card of an interface): a new interface.
   subroutine new_interface(cs, cur, line)
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(inout) :: cur   !! nif: the interfaces opened so far
      integer, intent(in) :: line          !! deck line of the card that opens it
      type(iface_spec_t), allocatable :: tmp(:)
      integer :: nif
      nif = cur%nif
      if (nif == size(cs%ifaces)) then
         ! room doubles (cut to size at the end of the block): linear in the cards
         allocate (tmp(max(4, 2*nif)))
         if (nif > 0) tmp(1:nif) = cs%ifaces(1:nif)
         call move_alloc(tmp, cs%ifaces)
      end if
      nif = nif + 1
      cur%nif = nif
      cs%ifaces(nif)%line = line
      cs%ifaces(nif)%law%line = line
      allocate (cs%ifaces(nif)%pairs(0))
   end subroutine new_interface
end module deck_contact
