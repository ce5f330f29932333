!> Readers of the TIES and CONTACT blocks of a deck (docs/deck-format.md).
!!
!! CONTACT holds keyword cards (keyword in columns 1-10, values in fields of
!! ten columns from column 11) and, after SURFACE and PAIRS cards, data cards
!! of node numbers or pairs.  Once the block is read, the pairs are built
!! (contact_definition) and the interface constants converted to model units
!! (contact_laws), so that every problem is reported with its deck line.
module deck_contact
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t
   use model, only: model_t
   use contact_types, only: LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, &
                            FRICTION_COULOMB, FRICTION_FREDRIKSSON, UNITS_KGF_UM, UNITS_N_UM, &
                            UNITS_MODEL, UPDATE_EXPLICIT, UPDATE_RETURN, SLIP_IRREVERSIBLE, SLIP_GROSS, &
                            NEWCLOSED_SECANT, NEWCLOSED_TANGENT, &
                            MATCH_NODE, MATCH_SEGMENT, rigid_body_t, RIGID_POLYLINE, RIGID_CIRCLE
   use contact_definition, only: iface_spec_t, define_contact
   implicit none
   private
   public :: read_ties, read_contact

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

   subroutine read_contact(d, ickw, m, warnings, is_block_card)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: warnings
      interface
         logical function is_block_card(d, ic)
            import :: deck_t
            type(deck_t), intent(in) :: d
            integer, intent(in) :: ic
         end function is_block_card
      end interface
      type(iface_spec_t), allocatable :: spec(:)
      type(rigid_body_t), allocatable :: rigids(:)
      integer :: ic, nif, mode, iside, nerr0
      character(len=:), allocatable :: key, w
      logical :: ok
      real(dp) :: v1, v2, v3, v4
      integer :: iv

      nerr0 = d%errors%n
      allocate (spec(0), rigids(0))
      nif = 0
      mode = 0          ! 0 none, 1 surface nodes, 2 pairs, 3 polyline vertices
      iside = 0
      do while (.not. d%at_end())
         if (is_block_card(d, d%peek())) exit
         ic = d%next()
         if (.not. d%is_keyword_card(ic)) then
            select case (mode)
            case (1)
               call read_node_list(ic)
            case (2)
               call read_pair(ic)
            case (3)
               call read_vertex(ic)
            case default
               call d%error_at(ic, 1, 'E-CARD', 'CONTACT: a data card must follow a SURFACE, PAIRS or RIGID POLYLINE '// &
                               'card, found "'// &
                               trim(d%cards(ic)%text)//'"')
            end select
            cycle
         end if
         ok = .true.
         call d%get_word(ic, 1, 10, 'CONTACT', 'KEYWORD', key, ok)
         mode = 0
         select case (key)
         case ('INTERFACE')
            call new_interface(ic)
         case ('LAW')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/LAW', 'LAW', w, ok)
            if (w == 'ROUGH') then
               spec(nif)%law%law = LAW_ROUGH
            else if (w == 'IDEAL') then
               spec(nif)%law%law = LAW_IDEAL
            else if (ok) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/LAW (columns 11-20) expected ROUGH or IDEAL, found "'//w//'"')
            end if
         case ('UNITS')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/UNITS', 'UNITS', w, ok)
            select case (w)
            case ('KGF_UM')
               spec(nif)%law%units = UNITS_KGF_UM
            case ('N_UM')
               spec(nif)%law%units = UNITS_N_UM
            case ('MODEL')
               spec(nif)%law%units = UNITS_MODEL
            case default
               if (ok) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/UNITS (columns 11-20) expected KGF_UM, N_UM '// &
                                       'or MODEL, found "'//w//'"')
            end select
         case ('NORMAL')
            call need_interface(ic)
            call d%get_real(ic, 11, 20, 'CONTACT/NORMAL', 'CN', v1, ok)
            call d%get_real(ic, 21, 30, 'CONTACT/NORMAL', 'M', v2, ok)
            call d%get_real(ic, 31, 40, 'CONTACT/NORMAL', 'CN2', v3, ok, default=-1.0_dp)
            call d%get_real(ic, 41, 50, 'CONTACT/NORMAL', 'M2', v4, ok, default=-1.0_dp)
            call tail(ic, 51, 'CN, M, CN2, M2 in columns 11-50', ok)
            if (ok) then
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
               spec(nif)%law%cn_in = v1
               spec(nif)%law%m_in = v2
               spec(nif)%law%cn2_in = v3
               spec(nif)%law%m2_in = v4
               spec(nif)%have_normal = .true.
            end if
         case ('TANGENT')
            call need_interface(ic)
            call d%get_real(ic, 11, 20, 'CONTACT/TANGENT', 'R', v1, ok, default=-1.0_dp)
            call d%get_real(ic, 21, 30, 'CONTACT/TANGENT', 'S', v2, ok, default=-1.0_dp)
            call tail(ic, 31, 'R, S in columns 11-30', ok)
            if (ok) then
               if (len_trim(d%field_text(ic, 11, 20)) > 0) then
                  if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/TANGENT: R (columns 11-20) '// &
                                                           'expected a positive constant, found '//rtoa(v1))
                  spec(nif)%law%r_in = v1
                  spec(nif)%law%r_given = .true.
               end if
               if (len_trim(d%field_text(ic, 21, 30)) > 0) then
                  if (v2 < 0.0_dp) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/TANGENT: S (columns 21-30) '// &
                                                   'expected an exponent >= 0, found '//rtoa(v2))
                  spec(nif)%law%s_in = v2
                  spec(nif)%law%s_given = .true.
               end if
            end if
         case ('FRICTION')
            call need_interface(ic)
            call read_friction(ic)
         case ('HARDENING')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/HARDENING', 'ON/OFF', w, ok)
            call d%get_real(ic, 21, 30, 'CONTACT/HARDENING', 'KAPPA', v1, ok, default=0.045_dp)
            call tail(ic, 31, 'ON or OFF and KAPPA in columns 11-30', ok)
            if (ok) then
               if (w == 'ON') then
                  spec(nif)%law%hardening = .true.
               else if (w == 'OFF') then
                  spec(nif)%law%hardening = .false.
               else
                  call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/HARDENING (columns 11-20) expected ON or OFF, found "'// &
                                  w//'"')
               end if
               if (.not. (v1 > 0.0_dp .and. v1 <= 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
                            'CONTACT/HARDENING: KAPPA (columns 21-30) expected a ratio k_T^p/k_T^e in (0, 1], found '// &
                            rtoa(v1))
               spec(nif)%law%kappa = v1
            end if
         case ('SLIP')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/SLIP', 'DEFINITION', w, ok)
            if (w == 'IRREVERSIBLE') then
               spec(nif)%law%slip_def = SLIP_IRREVERSIBLE
            else if (w == 'GROSS') then
               spec(nif)%law%slip_def = SLIP_GROSS
            else if (ok) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/SLIP (columns 11-20) expected IRREVERSIBLE or GROSS, '// &
                               'found "'//w//'"')
            end if
         case ('TOLERANCE')
            call need_interface(ic)
            call d%get_real(ic, 11, 20, 'CONTACT/TOLERANCE', 'TOL', v1, ok)
            if (ok .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/TOLERANCE (columns 11-20) '// &
                                                              'expected a positive distance, found '//rtoa(v1))
            if (ok) spec(nif)%law%tol = v1
         case ('SURFACE')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/SURFACE', 'SIDE', w, ok)
            iside = 0
            if (w == 'A') iside = 1
            if (w == 'B') iside = 2
            if (ok .and. iside == 0) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/SURFACE (columns 11-20) expected side A (upper body) '// &
                               'or B (lower body), found "'//w//'"')
            else if (ok) then
               if (spec(nif)%surf(iside)%given) then
                  call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/SURFACE: surface '//w//' of this interface is given twice')
               end if
               spec(nif)%surf(iside)%given = .true.
               spec(nif)%surf(iside)%line = d%cards(ic)%line
               if (.not. allocated(spec(nif)%surf(iside)%nodes)) allocate (spec(nif)%surf(iside)%nodes(0))
               w = trim(adjustl(d%field_text(ic, 21, 100000)))
               if (len(w) > 0) then
                  spec(nif)%surf(iside)%set_name = w
               else
                  mode = 1
               end if
            end if
         case ('PAIRS')
            call need_interface(ic)
            mode = 2
         case ('MATCHING')
            call need_interface(ic)
            call d%get_word(ic, 11, 20, 'CONTACT/MATCHING', 'MATCHING', w, ok)
            call tail(ic, 21, 'NODE or SEGMENT in columns 11-20', ok)
            if (ok) then
               if (w == 'NODE') then
                  spec(nif)%law%matching = MATCH_NODE
               else if (w == 'SEGMENT') then
                  spec(nif)%law%matching = MATCH_SEGMENT
               else
                  call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/MATCHING (columns 11-20) expected NODE '// &
                                  '(node-to-node pairs) or SEGMENT (nodes of A against edges of B), found "'//w//'"')
               end if
               if (spec(nif)%have_matching) call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT/MATCHING: given twice '// &
                                                            'for this interface')
               spec(nif)%have_matching = .true.
               spec(nif)%matching_line = d%cards(ic)%line
            end if
         case ('RIGID')
            call need_interface(ic)
            call read_rigid(ic)
         case ('AUGMENTED')
            call d%get_real(ic, 11, 20, 'CONTACT/AUGMENTED', 'FACTOR', v1, ok, default=100.0_dp)
            call d%get_real(ic, 21, 30, 'CONTACT/AUGMENTED', 'TOL', v2, ok, default=1.0e-6_dp)
            call tail(ic, 31, 'FACTOR and TOL in columns 11-30', ok)
            if (ok) then
               if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/AUGMENTED: FACTOR (columns '// &
                                                        '11-20) expected a positive penalty factor, found '//rtoa(v1))
               if (.not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/AUGMENTED: '// &
                            'TOL (columns 21-30) expected a tolerance in (0, 1) relative to the smallest contact '// &
                            'element, found '//rtoa(v2))
               m%contact%opts%aug_factor = v1
               m%contact%opts%aug_tol = v2
            end if
         case ('UPDATE', 'SCHEME')
            ! SCHEME INCREMENTAL (the paper) = UPDATE EXPLICIT; SCHEME NEWTON = UPDATE RETURN;
            ! SCHEME MODIFIED = RETURN with the stiffness kept (modified Newton)
            call d%get_word(ic, 11, 20, 'CONTACT/'//key, key, w, ok)
            select case (w)
            case ('EXPLICIT', 'INCREMENTA')
               m%contact%opts%update = UPDATE_EXPLICIT
               m%contact%opts%modified = .false.
            case ('RETURN', 'NEWTON')
               m%contact%opts%update = UPDATE_RETURN
               m%contact%opts%modified = .false.
            case ('MODIFIED')
               m%contact%opts%update = UPDATE_RETURN
               m%contact%opts%modified = .true.
            case default
               if (ok) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/'//key//' (columns 11-20) expected '// &
                                       'INCREMENTAL (or EXPLICIT), NEWTON (or RETURN) or MODIFIED, found "'//w//'"')
            end select
         case ('CONVERGE')
            call d%get_real(ic, 11, 20, 'CONTACT/CONVERGE', 'TOLR', v1, ok, default=1.0e-10_dp)
            call d%get_real(ic, 21, 30, 'CONTACT/CONVERGE', 'TOLU', v2, ok, default=1.0e-8_dp)
            call tail(ic, 31, 'TOLR, TOLU in columns 11-30', ok)
            if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
                   'CONTACT/CONVERGE: TOLR (columns 11-20) expected a relative force tolerance in (0, 1), found '//rtoa(v1))
            if (ok .and. .not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
                   'CONTACT/CONVERGE: TOLU (columns 21-30) expected a relative displacement tolerance in (0, 1), found '// &
                   rtoa(v2))
            if (ok) then
               m%contact%opts%tol_residual = v1
               m%contact%opts%tol_displacement = v2
            end if
         case ('FIRSTINC')
            call d%get_word(ic, 11, 20, 'CONTACT/FIRSTINC', 'RULE', w, ok)
            if (w == 'SECANT') then
               m%contact%opts%first_iterate = .false.
            else if (w == 'ITERATE') then
               m%contact%opts%first_iterate = .true.
            else if (ok) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/FIRSTINC (columns 11-20) expected SECANT or ITERATE, '// &
                               'found "'//w//'"')
            end if
         case ('NEWCLOSED')
            call d%get_word(ic, 11, 20, 'CONTACT/NEWCLOSED', 'RULE', w, ok)
            call d%get_real(ic, 21, 30, 'CONTACT/NEWCLOSED', 'PMIN', v1, ok, default=1.0e-3_dp)
            call tail(ic, 31, 'SECANT or TANGENT and PMIN in columns 11-30', ok)
            if (ok .and. w == 'SECANT') then
               m%contact%opts%newly_closed = NEWCLOSED_SECANT
            else if (ok .and. w == 'TANGENT') then
               m%contact%opts%newly_closed = NEWCLOSED_TANGENT
            else if (ok) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/NEWCLOSED (columns 11-20) expected SECANT or TANGENT, '// &
                               'found "'//w//'"')
            end if
            if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) then
               call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/NEWCLOSED: PMIN (columns 21-30) expected the floor '// &
                               'pressure as a fraction of p_m in (0, 1), found '//rtoa(v1))
            else if (ok) then
               m%contact%opts%p_min_ratio = v1
            end if
         case ('REPEATS')
            call d%get_int(ic, 11, 20, 'CONTACT/REPEATS', 'MAXREP', iv, ok)
            if (ok .and. (iv < 1 .or. iv > 10000)) then
               call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/REPEATS (columns 11-20) expected 1..10000, found '//itoa(iv))
            else if (ok) then
               m%contact%opts%max_repeats = iv
               m%contact%opts%repeats_given = .true.
            end if
         case ('START')
            call d%get_real(ic, 11, 20, 'CONTACT/START', 'PM', v1, ok, default=-1.0_dp)
            call d%get_int(ic, 21, 30, 'CONTACT/START', 'NSTART', iv, ok, default=0)
            call d%get_real(ic, 31, 40, 'CONTACT/START', 'GAPTOL', v2, ok, default=-1.0_dp)
            call tail(ic, 41, 'PM, NSTART, GAPTOL in columns 11-40', ok)
            if (ok) then
               if (len_trim(d%field_text(ic, 11, 20)) > 0 .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, 11, &
                            'E-CONTACT', 'CONTACT/START: PM (columns 11-20) expected a positive starting pressure, '// &
                            'found '//rtoa(v1))
               if (iv < 0) call d%error_at(ic, 21, 'E-CONTACT', 'CONTACT/START: NSTART (columns 21-30) expected a '// &
                                           'number of pairs >= 0, found '//itoa(iv))
               m%contact%opts%p_start = v1
               m%contact%opts%n_start = iv
               m%contact%opts%gap_tol = v2
            end if
         case default
            call d%error_at(ic, 1, 'E-CONTACT', 'CONTACT: unknown keyword "'//key//'" (expected INTERFACE, LAW, '// &
                            'UNITS, NORMAL, TANGENT, FRICTION, HARDENING, SLIP, SURFACE, PAIRS, MATCHING, RIGID, '// &
                            'TOLERANCE, SCHEME, UPDATE, CONVERGE, FIRSTINC, NEWCLOSED, REPEATS, START or AUGMENTED)')
         end select
      end do

      if (nif == 0) then
         call d%error_at(ickw, 1, 'E-CONTACT', 'CONTACT: the block defines no interface (expected at least NORMAL, '// &
                         'FRICTION and SURFACE or PAIRS cards)')
         return
      end if
      if (d%errors%n > nerr0) return
      m%contact%rigids = rigids
      call define_contact(m, spec, d%file, d%errors, warnings)
   contains
      !> RIGID card: SHAPE (11-20), NREF (21-30), then FLAT X1 Y1 X2 Y2 or
      !! CIRCLE XC YC R (31-70); POLYLINE takes its vertices from data cards.
      subroutine read_rigid(icard)
         integer, intent(in) :: icard
         character(len=:), allocatable :: shape
         integer :: nref
         real(dp) :: x(4)
         logical :: okr
         type(rigid_body_t) :: rb
         okr = .true.
         if (spec(nif)%law%rigid > 0) then
            call d%error_at(icard, 1, 'E-RIGID', 'CONTACT/RIGID: this interface already has a rigid body '// &
                            '(one RIGID card per interface; start another INTERFACE)')
            return
         end if
         call d%get_word(icard, 11, 20, 'CONTACT/RIGID', 'SHAPE', shape, okr)
         call d%get_int(icard, 21, 30, 'CONTACT/RIGID', 'NREF', nref, okr)
         if (.not. okr) return
         if (nref < 1 .or. nref > m%npoin) then
            call d%error_at(icard, 21, 'E-RANGE', 'CONTACT/RIGID: NREF (columns 21-30) expected the reference node '// &
                            '1..'//itoa(m%npoin)//', found '//itoa(nref))
            return
         end if
         rb%node = nref
         rb%line = d%cards(icard)%line
         select case (shape)
         case ('FLAT')
            call d%get_real(icard, 31, 40, 'CONTACT/RIGID', 'X1', x(1), okr)
            call d%get_real(icard, 41, 50, 'CONTACT/RIGID', 'Y1', x(2), okr)
            call d%get_real(icard, 51, 60, 'CONTACT/RIGID', 'X2', x(3), okr)
            call d%get_real(icard, 61, 70, 'CONTACT/RIGID', 'Y2', x(4), okr)
            call tail(icard, 71, 'FLAT, NREF, X1, Y1, X2, Y2 in columns 11-70', okr)
            if (.not. okr) return
            rb%shape = RIGID_POLYLINE
            rb%xy = reshape(x, [2, 2])
         case ('CIRCLE')
            call d%get_real(icard, 31, 40, 'CONTACT/RIGID', 'XC', x(1), okr)
            call d%get_real(icard, 41, 50, 'CONTACT/RIGID', 'YC', x(2), okr)
            call d%get_real(icard, 51, 60, 'CONTACT/RIGID', 'R', x(3), okr)
            call tail(icard, 61, 'CIRCLE, NREF, XC, YC, R in columns 11-60', okr)
            if (.not. okr) return
            if (.not. (x(3) > 0.0_dp)) then
               call d%error_at(icard, 51, 'E-RIGID', 'CONTACT/RIGID: R (columns 51-60) expected a positive radius, '// &
                               'found '//rtoa(x(3)))
               return
            end if
            rb%shape = RIGID_CIRCLE
            rb%centre = x(1:2)
            rb%radius = x(3)
            allocate (rb%xy(2, 0))
         case ('POLYLINE')
            call tail(icard, 31, 'POLYLINE and NREF in columns 11-30 (the vertices follow on data cards)', okr)
            if (.not. okr) return
            rb%shape = RIGID_POLYLINE
            allocate (rb%xy(2, 0))
            mode = 3
         case default
            call d%error_at(icard, 11, 'E-RIGID', 'CONTACT/RIGID: SHAPE (columns 11-20) expected FLAT, CIRCLE or '// &
                            'POLYLINE, found "'//shape//'"')
            return
         end select
         rigids = [rigids, rb]
         spec(nif)%law%rigid = size(rigids)
      end subroutine read_rigid

      !> A vertex of a POLYLINE profile: X (1-10), Y (11-20).
      subroutine read_vertex(icard)
         integer, intent(in) :: icard
         real(dp) :: x, y
         logical :: okv
         integer :: k
         okv = .true.
         call d%get_real(icard, 1, 10, 'CONTACT/RIGID', 'X', x, okv)
         call d%get_real(icard, 11, 20, 'CONTACT/RIGID', 'Y', y, okv)
         call tail(icard, 21, 'X, Y of a vertex in columns 1-20', okv)
         if (.not. okv) return
         k = size(rigids)
         rigids(k)%xy = reshape([reshape(rigids(k)%xy, [size(rigids(k)%xy)]), x, y], [2, size(rigids(k)%xy, 2) + 1])
      end subroutine read_vertex

      subroutine new_interface(icard)
         integer, intent(in) :: icard
         type(iface_spec_t), allocatable :: tmp(:)
         allocate (tmp(nif + 1))
         if (nif > 0) tmp(1:nif) = spec(1:nif)
         call move_alloc(tmp, spec)
         nif = nif + 1
         spec(nif)%line = d%cards(icard)%line
         spec(nif)%law%line = d%cards(icard)%line
         allocate (spec(nif)%pa(0), spec(nif)%pb(0), spec(nif)%pg0(0), spec(nif)%palpha(0), spec(nif)%parea(0), &
                   spec(nif)%has_g0(0), spec(nif)%has_alpha(0), spec(nif)%has_area(0), spec(nif)%pline(0))
      end subroutine new_interface

      !> Cards before the first INTERFACE card open interface 1.
      subroutine need_interface(icard)
         integer, intent(in) :: icard
         if (nif == 0) call new_interface(icard)
      end subroutine need_interface

      subroutine tail(icard, col, what, okay)
         integer, intent(in) :: icard, col
         character(len=*), intent(in) :: what
         logical, intent(inout) :: okay
         character(len=:), allocatable :: t
         t = trim(adjustl(d%field_text(icard, col, 100000)))
         if (len(t) > 0) then
            call d%error_at(icard, col, 'E-EXTRA', 'CONTACT: expected '//what//', found more: "'//t//'"')
            okay = .false.
         end if
      end subroutine tail

      subroutine read_friction(icard)
         integer, intent(in) :: icard
         logical :: okf
         character(len=:), allocatable :: kind
         real(dp) :: mu, beta, rate
         okf = .true.
         call d%get_word(icard, 11, 20, 'CONTACT/FRICTION', 'LAW', kind, okf)
         if (.not. okf) return
         ! FREDRIKSSON does not fit ten columns: any abbreviation of 4+ letters
         if (len(kind) >= 4 .and. len(kind) <= 11) then
            if (kind == 'FREDRIKSSON'(1:len(kind))) kind = 'FREDRIKSSON'
         end if
         select case (kind)
         case ('NONE')
            call tail(icard, 21, 'NONE alone', okf)
            spec(nif)%law%friction = FRICTION_NONE
            spec(nif)%law%mu_m = 0.0_dp
         case ('COULOMB')
            call d%get_real(icard, 21, 30, 'CONTACT/FRICTION', 'MU', mu, okf)
            call tail(icard, 31, 'COULOMB and MU in columns 11-30', okf)
            if (.not. okf) return
            if (.not. (mu >= 0.0_dp)) call d%error_at(icard, 21, 'E-CONTACT', 'CONTACT/FRICTION: MU (columns 21-30) '// &
                                                      'expected a friction coefficient >= 0, found '//rtoa(mu))
            spec(nif)%law%friction = FRICTION_COULOMB
            spec(nif)%law%mu_m = mu
            spec(nif)%law%beta = 1.0_dp
         case ('FREDRIKSSON')
            call d%get_real(icard, 21, 30, 'CONTACT/FRICTION', 'MU_M', mu, okf)
            call d%get_real(icard, 31, 40, 'CONTACT/FRICTION', 'BETA', beta, okf)
            call d%get_real(icard, 41, 50, 'CONTACT/FRICTION', 'N', rate, okf)
            call tail(icard, 51, 'FREDRIKSSON, MU_M, BETA, N in columns 11-50', okf)
            if (.not. okf) return
            if (.not. (mu >= 0.0_dp)) call d%error_at(icard, 21, 'E-CONTACT', 'CONTACT/FRICTION: MU_M (columns 21-30) '// &
                                                      'expected a friction coefficient >= 0, found '//rtoa(mu))
            if (.not. (beta > 0.0_dp .and. beta <= 1.0_dp)) call d%error_at(icard, 31, 'E-CONTACT', &
                         'CONTACT/FRICTION: BETA (columns 31-40) expected the initial fraction of mu_m in (0, 1], found '// &
                         rtoa(beta))
            if (.not. (rate >= 0.0_dp)) call d%error_at(icard, 41, 'E-CONTACT', 'CONTACT/FRICTION: N (columns 41-50) '// &
                                                        'expected a hardening rate >= 0 (1/length), found '//rtoa(rate))
            spec(nif)%law%friction = FRICTION_FREDRIKSSON
            spec(nif)%law%mu_m = mu
            spec(nif)%law%beta = beta
            spec(nif)%law%n_hard = rate
         case default
            call d%error_at(icard, 11, 'E-CONTACT', 'CONTACT/FRICTION (columns 11-20) expected NONE, COULOMB or '// &
                            'FREDRIKSSON, found "'//kind//'"')
            return
         end select
         spec(nif)%have_friction = .true.
      end subroutine read_friction

      subroutine read_node_list(icard)
         integer, intent(in) :: icard
         integer :: k, c1, node
         logical :: okn
         okn = .true.
         do k = 1, 16
            c1 = 1 + 5*(k - 1)
            if (len_trim(d%field_text(icard, c1, c1 + 4)) == 0) cycle
            call d%get_int(icard, c1, c1 + 4, 'CONTACT/SURFACE', 'NODE'//itoa(k), node, okn)
            if (.not. okn) return
            if (node < 1 .or. node > m%npoin) then
               call d%error_at(icard, c1, 'E-RANGE', 'CONTACT/SURFACE: node number (columns '//itoa(c1)//'-'// &
                               itoa(c1 + 4)//') expected 1..'//itoa(m%npoin)//', found '//itoa(node))
               cycle
            end if
            spec(nif)%surf(iside)%nodes = [spec(nif)%surf(iside)%nodes, node]
         end do
         if (len_trim(d%field_text(icard, 81, 100000)) > 0) call d%error_at(icard, 81, 'E-EXTRA', &
                                                  'CONTACT/SURFACE: at most 16 node numbers per card (columns 1-80)')
      end subroutine read_node_list

      subroutine read_pair(icard)
         integer, intent(in) :: icard
         integer :: na, nb
         real(dp) :: g0, alpha, area
         logical :: okp
         okp = .true.
         call d%get_int(icard, 1, 5, 'CONTACT/PAIRS', 'NODEA', na, okp)
         call d%get_int(icard, 6, 10, 'CONTACT/PAIRS', 'NODEB', nb, okp)
         call d%get_real(icard, 11, 20, 'CONTACT/PAIRS', 'G0', g0, okp, default=0.0_dp)
         call d%get_real(icard, 21, 30, 'CONTACT/PAIRS', 'ALPHA', alpha, okp, default=0.0_dp)
         call d%get_real(icard, 31, 40, 'CONTACT/PAIRS', 'AREA', area, okp, default=0.0_dp)
         call tail(icard, 41, 'NODEA, NODEB, G0, ALPHA, AREA in columns 1-40', okp)
         if (.not. okp) return
         if (na < 1 .or. na > m%npoin .or. nb < 1 .or. nb > m%npoin) then
            call d%error_at(icard, 1, 'E-RANGE', 'CONTACT/PAIRS: node numbers (columns 1-10) expected 1..'// &
                            itoa(m%npoin)//', found '//itoa(na)//' and '//itoa(nb))
            return
         end if
         if (len_trim(d%field_text(icard, 31, 40)) > 0 .and. .not. (area > 0.0_dp)) then
            call d%error_at(icard, 31, 'E-CONTACT', 'CONTACT/PAIRS: AREA (columns 31-40) expected a positive area, '// &
                            'found '//rtoa(area))
            return
         end if
         associate (s => spec(nif))
            s%npair = s%npair + 1
            s%pa = [s%pa, na]
            s%pb = [s%pb, nb]
            s%pg0 = [s%pg0, g0]
            s%palpha = [s%palpha, alpha]
            s%parea = [s%parea, area]
            s%has_g0 = [s%has_g0, len_trim(d%field_text(icard, 11, 20)) > 0]
            s%has_alpha = [s%has_alpha, len_trim(d%field_text(icard, 21, 30)) > 0]
            s%has_area = [s%has_area, len_trim(d%field_text(icard, 31, 40)) > 0]
            s%pline = [s%pline, d%cards(icard)%line]
         end associate
      end subroutine read_pair
   end subroutine read_contact

end module deck_contact
