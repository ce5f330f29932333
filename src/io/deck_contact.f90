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
   use strings, only: itoa, rtoa, same_name
   use deck_lexer, only: deck_t, shown
   use model, only: model_t, node_set_t
   use contact_types, only: interface_t, contact_options_t, LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, &
                            FRICTION_COULOMB, FRICTION_FREDRIKSSON, UNITS_KGF_UM, UNITS_N_UM, &
                            UNITS_MODEL, UPDATE_EXPLICIT, UPDATE_RETURN, SLIP_IRREVERSIBLE, SLIP_GROSS, &
                            NEWCLOSED_SECANT, NEWCLOSED_TANGENT, &
                            MATCH_NODE, MATCH_SEGMENT, rigid_body_t, RIGID_POLYLINE, RIGID_CIRCLE
   use contact_spec, only: contact_spec_t, iface_spec_t, surface_spec_t, pair_spec_t
   implicit none
   private
   public :: read_ties, read_contact

   ! What the data cards of the CONTACT block belong to: set by the last keyword card.
   integer, parameter :: DATA_NONE = 0       !! no data cards expected
   integer, parameter :: DATA_SURFACE = 1    !! node numbers of a SURFACE
   integer, parameter :: DATA_PAIRS = 2      !! explicit pairs after PAIRS
   integer, parameter :: DATA_VERTICES = 3   !! vertices of a RIGID POLYLINE

   !> Where the CONTACT reader is: the kind of data card expected next, and
   !! for DATA_SURFACE the side (1 A, 2 B) of the current interface.
   type :: contact_cursor_t
      integer :: mode = DATA_NONE
      integer :: iside = 0
      integer :: nif = 0            !! interfaces opened so far (cs%ifaces has room for more)
   end type contact_cursor_t

contains

   ! ------------------------------------------------------------------ TIES

   !> TIES: cards (CODE, N1, N2, ... N15): the listed nodes share N1's dofs.
   subroutine read_ties(d, m, is_block_card)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      interface
         logical function is_block_card(d, ic)
            import :: deck_t
            type(deck_t), intent(in) :: d
            integer, intent(in) :: ic
         end function is_block_card
      end interface
      integer, allocatable :: ties(:, :), master_of(:, :)
      logical, allocatable :: restrained(:, :)
      integer :: ic, code, k, node, nt, idof, c1, master, nlist, list(15)
      logical :: ok

      allocate (ties(3, 16), master_of(2, m%npoin), restrained(2, m%npoin))
      master_of = 0
      restrained = .false.
      do k = 1, size(m%fixes)
         restrained(:, m%fixes(k)%node) = restrained(:, m%fixes(k)%node) .or. m%fixes(k)%fixed
      end do
      nt = 0
      do while (.not. d%at_end())
         if (is_block_card(d, d%peek())) exit
         ic = d%next()
         ok = .true.
         call d%get_int(ic, 1, 5, 'TIES', 'CODE', code, ok)
         nlist = 0
         do k = 1, 15
            c1 = 6 + 5*(k - 1)
            if (len_trim(d%field_text(ic, c1, c1 + 4)) == 0) cycle
            nlist = nlist + 1
            call d%get_int(ic, c1, c1 + 4, 'TIES', 'N'//itoa(k), list(nlist), ok)
         end do
         if (len_trim(d%field_text(ic, 81, 100000)) > 0) then
            call d%error_at(ic, 81, 'E-EXTRA', 'TIES: expected CODE and at most 15 node numbers in columns 1-80')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (all(code /= [1, 10, 11])) then
            call d%error_at(ic, 1, 'E-CODE', 'TIES: CODE (columns 1-5) expected 10 (x), 01 (y) or 11 (both), found '// &
                            itoa(code))
            cycle
         end if
         if (nlist < 2) then
            call d%error_at(ic, 6, 'E-TIE', 'TIES: expected at least two node numbers (the first is the master), found '// &
                            itoa(nlist))
            cycle
         end if
         if (any(list(1:nlist) < 1 .or. list(1:nlist) > m%npoin)) then
            call d%error_at(ic, 6, 'E-RANGE', 'TIES: node numbers expected in 1..'//itoa(m%npoin))
            cycle
         end if
         do idof = 1, 2
            if (idof == 1 .and. code < 10) cycle
            if (idof == 2 .and. mod(code, 10) /= 1) cycle
            master = list(1)
            do while (master_of(idof, master) /= 0)
               master = master_of(idof, master)
            end do
            do k = 1, nlist
               node = list(k)
               if (restrained(idof, node)) then
                  call d%error_at(ic, 1 + 5*k, 'E-TIE', 'TIES: node '//itoa(node)//' is restrained in '// &
                                  merge('x', 'y', idof == 1)//'; ties act on free dofs only')
                  cycle
               end if
               if (k == 1) cycle
               if (node == master) cycle
               if (master_of(idof, node) /= 0) then
                  call d%error_at(ic, 1 + 5*k, 'E-TIE', 'TIES: node '//itoa(node)//' is tied twice in '// &
                                  merge('x', 'y', idof == 1))
                  cycle
               end if
               master_of(idof, node) = master
               if (nt >= size(ties, 2)) ties = reshape([ties, ties], [3, 2*size(ties, 2)])
               nt = nt + 1
               ties(:, nt) = [master, node, idof]
            end do
         end do
      end do
      ! a master that became a slave later: point its slaves at the final master
      do k = 1, nt
         master = ties(1, k)
         do while (master_of(ties(3, k), master) /= 0)
            master = master_of(ties(3, k), master)
         end do
         ties(1, k) = master
      end do
      m%ties = ties(:, 1:nt)
   end subroutine read_ties

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
            call d%error_at(ickw, 1, 'E-CONTACT', 'CONTACT: the block defines no interface (expected at least NORMAL, '// &
                            'FRICTION and SURFACE or PAIRS cards)')
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
      type(node_set_t), allocatable, intent(in) :: sets(:)   !! named node sets (MESH block), for RIGID's NREF
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(inout) :: cur
      character(len=*), parameter :: iface_cards(12) = [character(len=10) :: 'LAW', 'UNITS', 'NORMAL', &
                                     'TANGENT', 'FRICTION', 'HARDENING', 'SLIP', 'TOLERANCE', 'SURFACE', &
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
         call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT: unknown keyword "'//key//'" (expected INTERFACE, LAW, '// &
                         'UNITS, NORMAL, TANGENT, FRICTION, HARDENING, SLIP, SURFACE, PAIRS, MATCHING, RIGID, '// &
                         'TOLERANCE, SCHEME, UPDATE, CONVERGE, FIRSTINC, NEWCLOSED, REPEATS, START or AUGMENTED)')
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
               if (surf%nodes(k) >= 1 .and. surf%nodes(k) <= npoin) first_line(surf%nodes(k)) = surf%line
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
      call d%error_at(ic, 1, 'E-CARD', 'CONTACT: a data card must follow a SURFACE, PAIRS or RIGID POLYLINE '// &
                      'card, found "'//shown(trim(d%cards(ic)%text))//'"')
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

   !> Anything past the last field of a CONTACT card is an error.
   subroutine tail(d, ic, col, what, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, col
      character(len=*), intent(in) :: what   !! the fields the card has
      logical, intent(inout) :: ok
      character(len=:), allocatable :: t
      t = trim(adjustl(d%field_text(ic, col, 100000)))
      if (len(t) > 0) then
         call d%error_at(ic, col, 'E-EXTRA', 'CONTACT: expected '//what//', found more: "'//shown(t)//'"')
         ok = .false.
      end if
   end subroutine tail

   ! ------------------------------------------------------------------ CONTACT: the interface law

   !> LAW: ROUGH or IDEAL (11-20).
   subroutine read_law(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/LAW', 'LAW', w, ok)
      if (w == 'ROUGH') then
         law%law = LAW_ROUGH
      else if (w == 'IDEAL') then
         law%law = LAW_IDEAL
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/LAW (columns 11-20) expected ROUGH or IDEAL, found "'//w//'"')
      end if
   end subroutine read_law

   !> UNITS: KGF_UM, N_UM or MODEL (11-20), the units of CN and R.
   subroutine read_units(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/UNITS', 'UNITS', w, ok)
      select case (w)
      case ('KGF_UM')
         law%units = UNITS_KGF_UM
      case ('N_UM')
         law%units = UNITS_N_UM
      case ('MODEL')
         law%units = UNITS_MODEL
      case default
         if (ok) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/UNITS (columns 11-20) expected KGF_UM, N_UM '// &
                                 'or MODEL, found "'//w//'"')
      end select
   end subroutine read_units

   !> NORMAL: CN, M (loading) and CN2, M2 (unloading; default CN/2, M), in
   !! the interface's UNITS.
   subroutine read_normal(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      real(dp) :: v1, v2, v3, v4
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/NORMAL', 'CN', v1, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/NORMAL', 'M', v2, ok)
      call d%get_real(ic, 31, 40, 'CONTACT/NORMAL', 'CN2', v3, ok, default=-1.0_dp)
      call d%get_real(ic, 41, 50, 'CONTACT/NORMAL', 'M2', v4, ok, default=-1.0_dp)
      call tail(d, ic, 51, 'CN, M, CN2, M2 in columns 11-50', ok)
      if (.not. ok) return
      if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/NORMAL: CN (columns 11-20) '// &
                                               'expected a positive roughness constant c_n, found '//rtoa(v1))
      if (.not. (v2 > 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/NORMAL: M (columns 21-30) '// &
                                               'expected a positive exponent m, found '//rtoa(v2))
      if (v3 < 0.0_dp) v3 = 0.5_dp*v1
      if (v4 < 0.0_dp) v4 = v2
      if (.not. (v3 > 0.0_dp)) call d%error_at(ic, 31, 'E-CONTACT', 'CONTACT/NORMAL: CN2 (columns 31-40) '// &
                                               'expected a positive unloading constant, found '//rtoa(v3))
      if (.not. (v4 > 0.0_dp)) call d%error_at(ic, 41, 'E-CONTACT', 'CONTACT/NORMAL: M2 (columns 41-50) '// &
                                               'expected a positive unloading exponent, found '//rtoa(v4))
      if (abs(v4 - v2) <= 1.0e-12_dp*v2 .and. v3 > v1) call d%error_at(ic, 31, 'E-CONTACT', &
             'CONTACT/NORMAL: CN2 = '//rtoa(v3)//' > CN = '//rtoa(v1)//' with M2 = M: the unloading '// &
             'branch would be softer than loading and the residual closure negative (SPEC 2.1)')
      ! M2 < M: u_res = CN p_A^M - CN2 p_A^M2 < 0 for every reversal pressure p_A below
      ! (CN2/CN)^(1/(M - M2)), and every load path passes through small pressures
      if (v4 < v2*(1.0_dp - 1.0e-12_dp) .and. v2 > 0.0_dp .and. v3 > 0.0_dp) call d%error_at(ic, 41, 'E-CONTACT', &
             'CONTACT/NORMAL: M2 (columns 41-50) expected at least M = '//rtoa(v2)//', found '//rtoa(v4)// &
             ': with M2 < M the residual closure CN p_A^M - CN2 p_A^M2 is negative for every reversal '// &
             'pressure p_A below '//rtoa((v3/v1)**(1.0_dp/(v2 - v4)))//' (in the UNITS of the interface)')
      s%law%cn_in = v1
      s%law%m_in = v2
      s%law%cn2_in = v3
      s%law%m2_in = v4
      s%have_normal = .true.
   end subroutine read_normal

   !> TANGENT: R (11-20) and S (21-30); a blank field keeps the default
   !! (R from eq. 2.8, S = 1 - m).
   subroutine read_tangent(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/TANGENT', 'R', v1, ok, default=-1.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/TANGENT', 'S', v2, ok, default=-1.0_dp)
      call tail(d, ic, 31, 'R, S in columns 11-30', ok)
      if (.not. ok) return
      if (len_trim(d%field_text(ic, 11, 20)) > 0) then
         if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/TANGENT: R (columns 11-20) '// &
                                                  'expected a positive constant, found '//rtoa(v1))
         law%r_in = v1
         law%r_given = .true.
      end if
      if (len_trim(d%field_text(ic, 21, 30)) > 0) then
         if (v2 < 0.0_dp) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/TANGENT: S (columns 21-30) '// &
                                          'expected an exponent >= 0, found '//rtoa(v2))
         law%s_in = v2
         law%s_given = .true.
      end if
   end subroutine read_tangent

   !> FRICTION: NONE; COULOMB MU; or FREDRIKSSON MU_M BETA N (N in 1/length).
   subroutine read_friction(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      logical :: ok
      character(len=:), allocatable :: kind
      real(dp) :: mu, beta, rate
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/FRICTION', 'LAW', kind, ok)
      if (.not. ok) return
      ! FREDRIKSSON does not fit ten columns: any abbreviation of 4+ letters
      if (len(kind) >= 4 .and. len(kind) <= 11) then
         if (kind == 'FREDRIKSSON'(1:len(kind))) kind = 'FREDRIKSSON'
      end if
      select case (kind)
      case ('NONE')
         call tail(d, ic, 21, 'NONE alone', ok)
         s%law%friction = FRICTION_NONE
         s%law%mu_m = 0.0_dp
      case ('COULOMB')
         call d%get_real(ic, 21, 30, 'CONTACT/FRICTION', 'MU', mu, ok)
         call tail(d, ic, 31, 'COULOMB and MU in columns 11-30', ok)
         if (.not. ok) return
         if (.not. (mu >= 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/FRICTION: MU (columns 21-30) '// &
                                                   'expected a friction coefficient >= 0, found '//rtoa(mu))
         s%law%friction = FRICTION_COULOMB
         s%law%mu_m = mu
         s%law%beta = 1.0_dp
      case ('FREDRIKSSON')
         call d%get_real(ic, 21, 30, 'CONTACT/FRICTION', 'MU_M', mu, ok)
         call d%get_real(ic, 31, 40, 'CONTACT/FRICTION', 'BETA', beta, ok)
         call d%get_real(ic, 41, 50, 'CONTACT/FRICTION', 'N', rate, ok)
         call tail(d, ic, 51, 'FREDRIKSSON, MU_M, BETA, N in columns 11-50', ok)
         if (.not. ok) return
         if (.not. (mu >= 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/FRICTION: MU_M (columns 21-30) '// &
                                                   'expected a friction coefficient >= 0, found '//rtoa(mu))
         if (.not. (beta > 0.0_dp .and. beta <= 1.0_dp)) call d%error_at(ic, 31, 'E-CONTACT', &
                      'CONTACT/FRICTION: BETA (columns 31-40) expected the initial fraction of mu_m in (0, 1], found '// &
                      rtoa(beta))
         if (.not. (rate >= 0.0_dp)) call d%error_at(ic, 41, 'E-CONTACT', 'CONTACT/FRICTION: N (columns 41-50) '// &
                                                     'expected a hardening rate >= 0 (1/length), found '//rtoa(rate))
         s%law%friction = FRICTION_FREDRIKSSON
         s%law%mu_m = mu
         s%law%beta = beta
         s%law%n_hard = rate
      case default
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/FRICTION (columns 11-20) expected NONE, COULOMB or '// &
                         'FREDRIKSSON, found "'//kind//'"')
         return
      end select
      s%have_friction = .true.
   end subroutine read_friction

   !> HARDENING: ON or OFF (11-20) and KAPPA = k_T^p / k_T^e (21-30).
   subroutine read_hardening(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/HARDENING', 'ON/OFF', w, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/HARDENING', 'KAPPA', v1, ok, default=0.045_dp)
      call tail(d, ic, 31, 'ON or OFF and KAPPA in columns 11-30', ok)
      if (.not. ok) return
      if (w == 'ON') then
         law%hardening = .true.
      else if (w == 'OFF') then
         law%hardening = .false.
      else
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/HARDENING (columns 11-20) expected ON or OFF, found "'// &
                         w//'"')
      end if
      if (.not. (v1 > 0.0_dp .and. v1 <= 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
                   'CONTACT/HARDENING: KAPPA (columns 21-30) expected a ratio k_T^p/k_T^e in (0, 1], found '// &
                   rtoa(v1))
      law%kappa = v1
   end subroutine read_hardening

   !> SLIP: IRREVERSIBLE or GROSS (11-20), what the effective slip v_e counts.
   subroutine read_slip(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/SLIP', 'DEFINITION', w, ok)
      if (w == 'IRREVERSIBLE') then
         law%slip_def = SLIP_IRREVERSIBLE
      else if (w == 'GROSS') then
         law%slip_def = SLIP_GROSS
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/SLIP (columns 11-20) expected IRREVERSIBLE or GROSS, '// &
                         'found "'//w//'"')
      end if
   end subroutine read_slip

   !> TOLERANCE: the pairing tolerance TOL (11-20) [model length].
   subroutine read_tolerance(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/TOLERANCE', 'TOL', v1, ok)
      if (ok .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/TOLERANCE (columns 11-20) '// &
                                                        'expected a positive distance, found '//rtoa(v1))
      if (ok) law%tol = v1
   end subroutine read_tolerance

   ! ------------------------------------------------------------------ CONTACT: surfaces, pairs, rigid bodies

   !> SURFACE: side A or B (11-20), then a set name (21-) or node numbers on
   !! the data cards that follow.
   subroutine read_surface(d, ic, s, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      type(contact_cursor_t), intent(inout) :: cur
      character(len=:), allocatable :: w
      logical :: ok
      integer :: iside
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/SURFACE', 'SIDE', w, ok)
      iside = 0
      if (w == 'A') iside = 1
      if (w == 'B') iside = 2
      cur%iside = iside
      if (ok .and. iside == 0) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/SURFACE (columns 11-20) expected side A (upper body) '// &
                         'or B (lower body), found "'//w//'"')
      else if (ok) then
         if (s%surf(iside)%given) then
            call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/SURFACE: surface '//w//' of this interface is given twice')
         end if
         s%surf(iside)%given = .true.
         s%surf(iside)%line = d%cards(ic)%line
         if (.not. allocated(s%surf(iside)%nodes)) allocate (s%surf(iside)%nodes(0))
         w = trim(adjustl(d%field_text(ic, 21, 100000)))
         if (len(w) > 0) then
            s%surf(iside)%set_name = w
         else
            cur%mode = DATA_SURFACE
         end if
      end if
   end subroutine read_surface

   !> A data card of a SURFACE: up to 16 node numbers, I5 each, appended to
   !! nodes(1:nn); first_line(node) is the line where a node was listed first.
   subroutine read_node_list(d, ic, npoin, nodes, nn, first_line)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      integer, intent(inout) :: nodes(:)         !! room for 16 more
      integer, intent(inout) :: nn
      integer, intent(inout) :: first_line(:)    !! (npoin)
      integer :: k, c1, node
      logical :: ok
      ok = .true.
      do k = 1, 16
         c1 = 1 + 5*(k - 1)
         if (len_trim(d%field_text(ic, c1, c1 + 4)) == 0) cycle
         call d%get_int(ic, c1, c1 + 4, 'CONTACT/SURFACE', 'NODE'//itoa(k), node, ok)
         if (.not. ok) return
         if (node < 1 .or. node > npoin) then
            call d%error_at(ic, c1, 'E-RANGE', 'CONTACT/SURFACE: node number (columns '//itoa(c1)//'-'// &
                            itoa(c1 + 4)//') expected 1..'//itoa(npoin)//', found '//itoa(node))
            cycle
         end if
         if (first_line(node) /= 0) then
            call d%error_at(ic, c1, 'E-DUPLICATE', 'CONTACT/SURFACE: node '//itoa(node)//' (columns '// &
                            itoa(c1)//'-'//itoa(c1 + 4)//') is listed twice in this surface (first on line '// &
                            itoa(first_line(node))//')')
            cycle
         end if
         first_line(node) = d%cards(ic)%line
         nn = nn + 1
         nodes(nn) = node
      end do
      if (len_trim(d%field_text(ic, 81, 100000)) > 0) call d%error_at(ic, 81, 'E-EXTRA', &
                                                'CONTACT/SURFACE: at most 16 node numbers per card (columns 1-80)')
   end subroutine read_node_list

   !> A data card of PAIRS: NODEA, NODEB, G0, ALPHA (degrees), AREA.
   subroutine read_pair(d, ic, npoin, p, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(pair_spec_t), intent(out) :: p     !! the pair (when ok)
      logical, intent(out) :: ok              !! the card holds a valid pair
      integer :: na, nb
      real(dp) :: g0, alpha, area
      ok = .true.
      call d%get_int(ic, 1, 5, 'CONTACT/PAIRS', 'NODEA', na, ok)
      call d%get_int(ic, 6, 10, 'CONTACT/PAIRS', 'NODEB', nb, ok)
      call d%get_real(ic, 11, 20, 'CONTACT/PAIRS', 'G0', g0, ok, default=0.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/PAIRS', 'ALPHA', alpha, ok, default=0.0_dp)
      call d%get_real(ic, 31, 40, 'CONTACT/PAIRS', 'AREA', area, ok, default=0.0_dp)
      call tail(d, ic, 41, 'NODEA, NODEB, G0, ALPHA, AREA in columns 1-40', ok)
      if (.not. ok) return
      if (na < 1 .or. na > npoin .or. nb < 1 .or. nb > npoin) then
         call d%error_at(ic, 1, 'E-RANGE', 'CONTACT/PAIRS: node numbers (columns 1-10) expected 1..'// &
                         itoa(npoin)//', found '//itoa(na)//' and '//itoa(nb))
         ok = .false.
         return
      end if
      if (len_trim(d%field_text(ic, 31, 40)) > 0 .and. .not. (area > 0.0_dp)) then
         call d%error_at(ic, 31, 'E-CONTACT', 'CONTACT/PAIRS: AREA (columns 31-40) expected a positive area, '// &
                         'found '//rtoa(area))
         ok = .false.
         return
      end if
      p = pair_spec_t(node_a=na, node_b=nb, g0=g0, alpha=alpha, area=area, &
                      has_g0=len_trim(d%field_text(ic, 11, 20)) > 0, &
                      has_alpha=len_trim(d%field_text(ic, 21, 30)) > 0, &
                      has_area=len_trim(d%field_text(ic, 31, 40)) > 0, line=d%cards(ic)%line)
   end subroutine read_pair

   !> MATCHING: NODE (node-to-node pairs) or SEGMENT (nodes of A against edges of B).
   subroutine read_matching(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/MATCHING', 'MATCHING', w, ok)
      call tail(d, ic, 21, 'NODE or SEGMENT in columns 11-20', ok)
      if (.not. ok) return
      if (w == 'NODE') then
         s%law%matching = MATCH_NODE
      else if (w == 'SEGMENT') then
         s%law%matching = MATCH_SEGMENT
      else
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/MATCHING (columns 11-20) expected NODE '// &
                         '(node-to-node pairs) or SEGMENT (nodes of A against edges of B), found "'//w//'"')
      end if
      if (s%have_matching) call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/MATCHING: given twice '// &
                                           'for this interface')
      s%have_matching = .true.
      s%matching_line = d%cards(ic)%line
   end subroutine read_matching

   !> RIGID: SHAPE (11-20), NREF (21-30), then FLAT X1 Y1 X2 Y2 or CIRCLE XC
   !! YC R (31-70) [model length]; POLYLINE takes its vertices from data cards.
   !! The body becomes side B of the current interface.  NREF may instead be
   !! the name of a node set of one node (a MESH block's NODE card).
   subroutine read_rigid(d, ic, npoin, sets, cs, cur)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic, npoin
      type(node_set_t), allocatable, intent(in) :: sets(:)
      type(contact_spec_t), intent(inout) :: cs
      type(contact_cursor_t), intent(inout) :: cur
      character(len=:), allocatable :: shape
      integer :: nref, nif
      real(dp) :: x(4)
      integer :: k
      character(len=2), parameter :: fnames(4) = ['X1', 'Y1', 'X2', 'Y2'], cnames(3) = ['XC', 'YC', 'R ']
      logical :: ok
      type(rigid_body_t) :: rb
      ok = .true.
      nif = cur%nif
      if (cs%ifaces(nif)%law%rigid > 0) then
         call d%error_at(ic, 1, 'E-RIGID', 'CONTACT/RIGID: this interface already has a rigid body '// &
                         '(one RIGID card per interface; start another INTERFACE)')
         return
      end if
      call d%get_word(ic, 11, 20, 'CONTACT/RIGID', 'SHAPE', shape, ok)
      call reference_node(d, ic, sets, nref, ok)
      if (.not. ok) return
      if (nref < 1 .or. nref > npoin) then
         call d%error_at(ic, 21, 'E-RANGE', 'CONTACT/RIGID: NREF (columns 21-30) expected the reference node '// &
                         '1..'//itoa(npoin)//', found '//itoa(nref))
         return
      end if
      rb%node = nref
      rb%line = d%cards(ic)%line
      select case (shape)
      case ('FLAT')
         call d%get_real(ic, 31, 40, 'CONTACT/RIGID', 'X1', x(1), ok)
         call d%get_real(ic, 41, 50, 'CONTACT/RIGID', 'Y1', x(2), ok)
         call d%get_real(ic, 51, 60, 'CONTACT/RIGID', 'X2', x(3), ok)
         call d%get_real(ic, 61, 70, 'CONTACT/RIGID', 'Y2', x(4), ok)
         call tail(d, ic, 71, 'FLAT, NREF, X1, Y1, X2, Y2 in columns 11-70', ok)
         do k = 1, 4
            call d%check_coordinate(ic, 21 + 10*k, 'CONTACT/RIGID', trim(fnames(k)), x(k), ok)
         end do
         if (.not. ok) return
         rb%shape = RIGID_POLYLINE
         rb%xy = reshape(x, [2, 2])
      case ('CIRCLE')
         call d%get_real(ic, 31, 40, 'CONTACT/RIGID', 'XC', x(1), ok)
         call d%get_real(ic, 41, 50, 'CONTACT/RIGID', 'YC', x(2), ok)
         call d%get_real(ic, 51, 60, 'CONTACT/RIGID', 'R', x(3), ok)
         call tail(d, ic, 61, 'CIRCLE, NREF, XC, YC, R in columns 11-60', ok)
         do k = 1, 3
            call d%check_coordinate(ic, 21 + 10*k, 'CONTACT/RIGID', trim(cnames(k)), x(k), ok)
         end do
         if (.not. ok) return
         if (.not. (x(3) > 0.0_dp)) then
            call d%error_at(ic, 51, 'E-RIGID', 'CONTACT/RIGID: R (columns 51-60) expected a positive radius, '// &
                            'found '//rtoa(x(3)))
            return
         end if
         rb%shape = RIGID_CIRCLE
         rb%centre = x(1:2)
         rb%radius = x(3)
         allocate (rb%xy(2, 0))
      case ('POLYLINE')
         call tail(d, ic, 31, 'POLYLINE and NREF in columns 11-30 (the vertices follow on data cards)', ok)
         if (.not. ok) return
         rb%shape = RIGID_POLYLINE
         allocate (rb%xy(2, 0))
         cur%mode = DATA_VERTICES
      case default
         call d%error_at(ic, 11, 'E-RIGID', 'CONTACT/RIGID: SHAPE (columns 11-20) expected FLAT, CIRCLE or '// &
                         'POLYLINE, found "'//shape//'"')
         return
      end select
      cs%rigids = [cs%rigids, rb]
      cs%ifaces(nif)%law%rigid = size(cs%rigids)
   end subroutine read_rigid

   !> RIGID's NREF (columns 21-30): a node number, or the name of a node set
   !! of exactly one node (the extra node of a MESH block's NODE card).
   subroutine reference_node(d, ic, sets, nref, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(node_set_t), allocatable, intent(in) :: sets(:)
      integer, intent(out) :: nref
      logical, intent(inout) :: ok
      character(len=:), allocatable :: f
      integer :: k
      nref = 0
      f = trim(adjustl(d%field_text(ic, 21, 30)))
      if (len(f) == 0 .or. verify(f(1:1), 'abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ_') /= 0) then
         call d%get_int(ic, 21, 30, 'CONTACT/RIGID', 'NREF', nref, ok)
         return
      end if
      if (allocated(sets)) then
         do k = 1, size(sets)
            if (.not. same_name(sets(k)%name, f)) cycle
            if (size(sets(k)%nodes) /= 1) then
               call d%error_at(ic, 21, 'E-RIGID', 'CONTACT/RIGID: NREF (columns 21-30) names the set "'//f// &
                               '" of '//itoa(size(sets(k)%nodes))//' nodes; expected one node (a NODE card of '// &
                               'the MESH block)')
               ok = .false.
               return
            end if
            nref = sets(k)%nodes(1)
            return
         end do
      end if
      call d%error_at(ic, 21, 'E-RIGID', 'CONTACT/RIGID: NREF (columns 21-30) expected a node number or the name '// &
                      'of an extra node (MESH block, NODE card), found "'//shown(f)//'"')
      ok = .false.
   end subroutine reference_node

   !> A vertex of a POLYLINE profile: X (1-10), Y (11-20) [model length].
   subroutine read_vertex(d, ic, xy, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      real(dp), intent(out) :: xy(2)          !! the vertex (when ok)
      logical, intent(out) :: ok              !! the card holds a valid vertex
      ok = .true.
      call d%get_real(ic, 1, 10, 'CONTACT/RIGID', 'X', xy(1), ok)
      call d%get_real(ic, 11, 20, 'CONTACT/RIGID', 'Y', xy(2), ok)
      call d%check_coordinate(ic, 1, 'CONTACT/RIGID', 'X', xy(1), ok)
      call d%check_coordinate(ic, 11, 'CONTACT/RIGID', 'Y', xy(2), ok)
      call tail(d, ic, 21, 'X, Y of a vertex in columns 1-20', ok)
   end subroutine read_vertex

   ! ------------------------------------------------------------------ CONTACT: algorithm options

   !> AUGMENTED: penalty FACTOR (11-20) and TOL (21-30) of the ideal contact.
   subroutine read_augmented(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/AUGMENTED', 'FACTOR', v1, ok, default=100.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/AUGMENTED', 'TOL', v2, ok, default=1.0e-6_dp)
      call tail(d, ic, 31, 'FACTOR and TOL in columns 11-30', ok)
      if (.not. ok) return
      if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/AUGMENTED: FACTOR (columns '// &
                                               '11-20) expected a positive penalty factor, found '//rtoa(v1))
      if (.not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/AUGMENTED: '// &
                   'TOL (columns 21-30) expected a tolerance in (0, 1) relative to the smallest contact '// &
                   'element, found '//rtoa(v2))
      opts%aug_factor = v1
      opts%aug_tol = v2
   end subroutine read_augmented

   !> UPDATE or SCHEME (key): SCHEME INCREMENTAL (the paper) = UPDATE
   !! EXPLICIT; SCHEME NEWTON = UPDATE RETURN; SCHEME MODIFIED = RETURN with
   !! the stiffness kept (modified Newton).
   subroutine read_update(d, ic, key, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      character(len=*), intent(in) :: key    !! UPDATE or SCHEME, for messages
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/'//key, key, w, ok)
      select case (w)
      case ('EXPLICIT', 'INCREMENTA')
         opts%update = UPDATE_EXPLICIT
         opts%modified = .false.
      case ('RETURN', 'NEWTON')
         opts%update = UPDATE_RETURN
         opts%modified = .false.
      case ('MODIFIED')
         opts%update = UPDATE_RETURN
         opts%modified = .true.
      case default
         if (ok) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/'//key//' (columns 11-20) expected '// &
                                 'INCREMENTAL (or EXPLICIT), NEWTON (or RETURN) or MODIFIED, found "'//w//'"')
      end select
   end subroutine read_update

   !> CONVERGE: relative force TOLR (11-20) and displacement TOLU (21-30) tolerances.
   subroutine read_converge(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/CONVERGE', 'TOLR', v1, ok, default=1.0e-10_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/CONVERGE', 'TOLU', v2, ok, default=1.0e-8_dp)
      call tail(d, ic, 31, 'TOLR, TOLU in columns 11-30', ok)
      if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
             'CONTACT/CONVERGE: TOLR (columns 11-20) expected a relative force tolerance in (0, 1), found '//rtoa(v1))
      if (ok .and. .not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
             'CONTACT/CONVERGE: TOLU (columns 21-30) expected a relative displacement tolerance in (0, 1), found '// &
             rtoa(v2))
      if (ok) then
         opts%tol_residual = v1
         opts%tol_displacement = v2
      end if
   end subroutine read_converge

   !> FIRSTINC: SECANT or ITERATE (11-20), the rule of the first increment.
   subroutine read_firstinc(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/FIRSTINC', 'RULE', w, ok)
      if (w == 'SECANT') then
         opts%first_iterate = .false.
      else if (w == 'ITERATE') then
         opts%first_iterate = .true.
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/FIRSTINC (columns 11-20) expected SECANT or ITERATE, '// &
                         'found "'//w//'"')
      end if
   end subroutine read_firstinc

   !> NEWCLOSED: SECANT or TANGENT (11-20) and PMIN (21-30), a fraction of p_m.
   subroutine read_newclosed(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/NEWCLOSED', 'RULE', w, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/NEWCLOSED', 'PMIN', v1, ok, default=1.0e-3_dp)
      call tail(d, ic, 31, 'SECANT or TANGENT and PMIN in columns 11-30', ok)
      if (ok .and. w == 'SECANT') then
         opts%newly_closed = NEWCLOSED_SECANT
      else if (ok .and. w == 'TANGENT') then
         opts%newly_closed = NEWCLOSED_TANGENT
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/NEWCLOSED (columns 11-20) expected SECANT or TANGENT, '// &
                         'found "'//w//'"')
      end if
      if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) then
         call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/NEWCLOSED: PMIN (columns 21-30) expected the floor '// &
                         'pressure as a fraction of p_m in (0, 1), found '//rtoa(v1))
      else if (ok) then
         opts%p_min_ratio = v1
      end if
   end subroutine read_newclosed

   !> REPEATS: MAXREP (11-20), the cap on repeats of one increment.
   subroutine read_repeats(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      integer :: iv
      logical :: ok
      ok = .true.
      call d%get_int(ic, 11, 20, 'CONTACT/REPEATS', 'MAXREP', iv, ok)
      if (ok .and. (iv < 1 .or. iv > 10000)) then
         call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/REPEATS (columns 11-20) expected 1..10000, found '//itoa(iv))
      else if (ok) then
         opts%max_repeats = iv
         opts%repeats_given = .true.
      end if
   end subroutine read_repeats

   !> START: starting pressure PM (11-20) [model stress], NSTART (21-30) and
   !! GAPTOL (31-40) [model length].
   subroutine read_start(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      integer :: iv
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/START', 'PM', v1, ok, default=-1.0_dp)
      call d%get_int(ic, 21, 30, 'CONTACT/START', 'NSTART', iv, ok, default=0)
      call d%get_real(ic, 31, 40, 'CONTACT/START', 'GAPTOL', v2, ok, default=-1.0_dp)
      call tail(d, ic, 41, 'PM, NSTART, GAPTOL in columns 11-40', ok)
      if (.not. ok) return
      if (len_trim(d%field_text(ic, 11, 20)) > 0 .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, 11, &
                   'E-CONTACT', 'CONTACT/START: PM (columns 11-20) expected a positive starting pressure, '// &
                   'found '//rtoa(v1))
      if (iv < 0) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/START: NSTART (columns 21-30) expected a '// &
                                  'number of pairs >= 0, found '//itoa(iv))
      opts%p_start = v1
      opts%n_start = iv
      opts%gap_tol = v2
   end subroutine read_start

end module deck_contact
