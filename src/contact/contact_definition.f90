!> Contact definition: from the deck's contact specification to the pairs.
!!
!! `define_contact` runs after the deck is read (driver/model_input).  For
!! every interface of `m%contact_spec` it checks that the cards fit together,
!! builds the pairs (contact_pairing: node to node, or by projection on the
!! edges of surface B or on a rigid profile, with the lumped areas of
!! contact_surfaces), gives each pair the contact modulus of its two bodies,
!! and converts the interface constants to model units with R per pair
!! (contact_laws, eq. 2.8).  Then it checks the pairs of all interfaces
!! together.  The result is the model's `contact` (contact_types): the
!! interfaces in model units, the pairs, the rigid bodies and the options.
!!
!! Every problem is reported into the reader's error list at the deck line
!! of the card it comes from, so that a rejected definition reads like a
!! rejected card.  A new kind of side B is a new builder in contact_pairing
!! and one branch in `define_contact`.
!!
!! Ref: Altenbach & Buczkowski, eqs. (2.8), (3.8), (3.22); SPEC §2.4 (units), §3.2 (areas).
module contact_definition
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use model, only: model_t, NTYPE_AXISYMMETRIC
   use contact_types, only: contact_pair_t, interface_t, rigid_body_t, LAW_ROUGH, PAIR_NODE, &
         PAIR_RIGID, &
                            MATCH_SEGMENT, RIGID_CIRCLE, UNITS_KGF_UM, UNITS_N_UM, KGF_PER_NMM2
   use contact_spec, only: iface_spec_t
   use contact_laws, only: convert_interface, admissible_reversals
   use contact_pairing, only: node_pairs, projected_pairs, E_COARSE_SIDE
   use restraint_check, only: find_bodies
   implicit none
   private
   public :: define_contact, node_modulus

contains

   !> Build the pairs of every interface from the model's contact
   !! specification, check them and convert the interface constants to model
   !! units.  Problems go to `errors` / `warnings`, located at the spec's
   !! lines in the deck.
   subroutine define_contact(m, errors, warnings)
      type(model_t), intent(inout) :: m                  !! contact_spec read; contact filled
      type(error_list_t), intent(inout) :: errors
      type(error_list_t), intent(inout) :: warnings
      type(contact_pair_t), allocatable :: pairs(:)
      real(dp), allocatable :: young(:), nu(:)
      character(len=:), allocatable :: file
      real(dp) :: size_model, tol
      integer :: i, np0, n0
      logical :: ok, swapped

      n0 = errors%n
      file = m%deck_file
      allocate (pairs(0), young(m%npoin), nu(m%npoin))
      call node_modulus(m, young, nu)
      size_model = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), &
                       maxval(m%coord(2, :)) - minval(m%coord(2, :)))
      m%contact%rigids = m%contact_spec%rigids
      m%contact%opts = m%contact_spec%opts
      call check_rigids(m, m%contact%rigids, size_model, file, errors)
      if (allocated(m%contact%ifaces)) deallocate (m%contact%ifaces)
      allocate (m%contact%ifaces(size(m%contact_spec%ifaces)))
      do i = 1, size(m%contact_spec%ifaces)
         associate (s => m%contact_spec%ifaces(i))
            if (.not. cards_fit(s, i, file, errors)) cycle
            np0 = size(pairs)
            tol = s%law%tol
            if (tol <= 0.0_dp) tol = 1.0e-6_dp*size_model
            swapped = .false.
            if (s%law%rigid > 0) then
               call projected_pairs(m, s, i, tol, size_model, file, pairs, errors, ok)
            else if (s%law%matching == MATCH_SEGMENT) then
               call segment_pairs(m, s, i, tol, size_model, file, pairs, errors, ok, swapped)
            else
               call node_pairs(m, s, i, tol, file, pairs, errors, ok)
            end if
            if (.not. ok) cycle
            m%contact%ifaces(i) = s%law
            m%contact%ifaces(i)%sides_swapped = swapped
            call define_law(young, nu, pairs(np0 + 1:), m%contact%ifaces(i), s%line, file, errors)
         end associate
      end do
      if (errors%n > n0) return
      call check_pairs(m, pairs, size_model, file, errors, warnings)
      m%contact%pairs = pairs
      m%contact%active = size(pairs) > 0
   end subroutine define_contact

   !> MATCHING SEGMENT pairs of interface iface: the nodes of SURFACE A
   !! projected on the edges of SURFACE B.  Where that fails only because a
   !! node of A faces more nodes of B than a pair holds (A is the coarser
   !! side), the other way round: the nodes of B on the edges of A, and
   !! `swapped` says so (the listing reports it).  If neither works, the
   !! errors of the deck's own direction are reported.
   subroutine segment_pairs(m, s, iface, tol, size_model, file, pairs, errors, ok, swapped)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s               !! the interface as the deck gives it
      integer, intent(in) :: iface                      !! its number
      real(dp), intent(in) :: tol, size_model           !! pairing tolerance, model size [length]
      character(len=*), intent(in) :: file
      type(contact_pair_t), allocatable, intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      logical, intent(out) :: swapped                   !! the pairs were built from B's nodes
      type(error_list_t) :: direct, other
      type(iface_spec_t) :: t
      integer :: np0, k
      logical :: coarse_only

      swapped = .false.
      np0 = size(pairs)
      call projected_pairs(m, s, iface, tol, size_model, file, pairs, direct, ok)
      ok = ok .and. direct%n == 0      ! a rejected node is reported, not counted as unmatched
      if (ok) return
      coarse_only = direct%n > 0
      do k = 1, direct%n
         if (direct%items(k)%code /= E_COARSE_SIDE) coarse_only = .false.
      end do
      if (coarse_only) then
         pairs = pairs(1:np0)
         t = s
         t%surf(1) = s%surf(2)
         t%surf(2) = s%surf(1)
         call projected_pairs(m, t, iface, tol, size_model, file, pairs, other, ok)
         swapped = ok .and. other%n == 0
         if (swapped) return
         pairs = pairs(1:np0)
      end if
      ok = .false.
      do k = 1, direct%n
         associate (e => direct%items(k))
            call errors%add(e%code, e%message, file=e%file, line=e%line, col=e%col, card=e%card)
         end associate
      end do
   end subroutine segment_pairs

   !> Checks of the rigid bodies: the reference node belongs to no element,
   !! a polyline has two or more distinct vertices.
   subroutine check_rigids(m, rigids, size_model, file, errors)
      type(model_t), intent(in) :: m
      type(rigid_body_t), intent(in) :: rigids(:)
      real(dp), intent(in) :: size_model          !! model size [length]: vertices
                                                  !! closer than 1e-12 of it coincide
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      logical :: in_elem(m%npoin)
      integer :: ie, r, v
      in_elem = .false.
      do ie = 1, m%nelem
         in_elem(m%lnods(1:m%nnode_e(ie), ie)) = .true.
      end do
      do r = 1, size(rigids)
         associate (rb => rigids(r))
            if (in_elem(rb%node)) call errors%add('E-RIGID', &
                                                  'CONTACT/RIGID: reference node '// &
                                                  itoa(rb%node)// &
                                                  ' belongs to an element; the reference node of a &
                                                  &rigid body '// &
                                                  'must be a node of no element', file=file, &
                                                  line=rb%line)
            if (rb%shape == RIGID_CIRCLE) cycle
            if (size(rb%xy, 2) < 2) then
               call errors%add('E-RIGID', &
                               'CONTACT/RIGID: a polyline profile needs at least two vertices '// &
                               '(X, Y cards after the RIGID card), found '//itoa(size(rb%xy, 2)), &
                               file=file, line=rb%line)
            else
               do v = 1, size(rb%xy, 2) - 1
                  if (norm2(rb%xy(:, v + 1) - rb%xy(:, v)) <= 1.0e-12_dp*size_model) then
                     call errors%add('E-RIGID', 'CONTACT/RIGID: vertices '//itoa(v)//' and '// &
                                     itoa(v + 1)// &
                                     ' of the profile coincide', file=file, line=rb%line)
                  end if
               end do
            end if
         end associate
      end do
   end subroutine check_rigids

   !> Do the cards of interface i fit together?  Reports what is missing or
   !! contradictory; false where no pairs can be built (a missing NORMAL or
   !! FRICTION card is reported, but the pairs are still built and checked).
   logical function cards_fit(s, i, file, errors) result(ok)
      type(iface_spec_t), intent(in) :: s
      integer, intent(in) :: i
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      logical :: both

      ok = .false.
      if (s%law%law == LAW_ROUGH .and. .not. s%have_normal) then
         call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)// &
                         ' (rough) has no NORMAL card '// &
                         '(CN, M, CN2, M2)', file=file, line=s%line)
      end if
      if (.not. s%have_friction) then
         call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' has no FRICTION card '// &
                         '(NONE, COULOMB mu, or FREDRIKSSON mu_m beta n)', file=file, line=s%line)
      end if
      both = s%surf(1)%given .and. s%surf(2)%given
      if (s%law%rigid > 0) then
         if (s%surf(2)%given) call errors%add('E-RIGID', &
                                              'CONTACT: interface '//itoa(i)// &
                                              ' has a RIGID body '// &
                                              'and a SURFACE B: the rigid body is side B, give &
                                              &only SURFACE A '// &
                                              '(the deformable surface facing it)', file=file, &
                                              line=s%surf(2)%line)
         if (size(s%pairs) > 0) call errors%add('E-RIGID', &
                                                'CONTACT: interface '//itoa(i)// &
                                                ' has a RIGID body: '// &
                                                'its pairs are built from SURFACE A, PAIRS cannot &
                                                &be given', &
                                                file=file, line=s%pairs(1)%line)
         if (s%have_matching) call errors%add('E-RIGID', &
                                              'CONTACT: interface '//itoa(i)// &
                                              ': MATCHING applies '// &
                                              'to a SURFACE B; the nodes of SURFACE A are always &
                                              &projected on a '// &
                                              'rigid profile', file=file, line=s%matching_line)
         if (.not. s%surf(1)%given) then
            call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)// &
                            ' has a RIGID body but no SURFACE A '// &
                            '(the deformable surface facing it)', file=file, line=s%line)
            return
         end if
         if (s%surf(2)%given .or. size(s%pairs) > 0 .or. s%have_matching) return
      else if (s%law%matching == MATCH_SEGMENT) then
         if (size(s%pairs) > 0) call errors%add('E-CONTACT', &
                                                'CONTACT: interface '//itoa(i)//': PAIRS are '// &
                                                'node-to-node; MATCHING SEGMENT builds its pairs &
                                                &from SURFACE A '// &
                                                'and SURFACE B', file=file, line=s%pairs(1)%line)
         if (.not. both) then
            call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)// &
                            ' (MATCHING SEGMENT) needs SURFACE A '// &
                            'and SURFACE B cards', file=file, line=s%line)
            return
         end if
         if (size(s%pairs) > 0) return
      else if (size(s%pairs) == 0 .and. .not. both) then
         call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)// &
                         ' needs SURFACE A and SURFACE B cards, '// &
                         'PAIRS, or SURFACE A and a RIGID body', file=file, line=s%line)
         return
      end if
      ok = .true.
   end function cards_fit

   !> The law of one interface in model units, and the moduli of its pairs:
   !! the contact modulus E* (the ideal law's penalty scale) and, for R of
   !! eq. (2.8), the Poisson ratio of the pair (mean of the two bodies; that
   !! of body A against a rigid body).
   !!
   !! Ref: Altenbach & Buczkowski, eq. (2.8); SPEC §2.4.
   subroutine define_law(young, nu, pairs, law, line, file, errors)
      real(dp), intent(in) :: young(:), nu(:)        !! (npoin) E [stress] and nu [-] at every node
      type(contact_pair_t), intent(inout) :: pairs(:)   !! the interface's pairs: estar [stress] set
      type(interface_t), intent(inout) :: law        !! as given; converted to
                                                     !! model units, r_t per pair
      integer, intent(in) :: line                    !! deck line of the interface
      character(len=*), intent(in) :: file           !! the deck
      type(error_list_t), intent(inout) :: errors    !! constants out of range (law_constants_fit)
      real(dp) :: nu_pair(size(pairs))
      real(dp) :: p_lo
      integer :: k
      do k = 1, size(pairs)
         associate (p => pairs(k))
            if (p%kind == PAIR_RIGID) then
               nu_pair(k) = nu(p%node_a)
               p%estar = young(p%node_a)/(1.0_dp - nu(p%node_a)**2)
            else
               nu_pair(k) = 0.5_dp*(nu(p%node_a) + nu(p%nodes(2)))
               p%estar = 1.0_dp/((1.0_dp - nu(p%node_a)**2)/young(p%node_a) + &
                                 (1.0_dp - nu(p%nodes(2))**2)/young(p%nodes(2)))
            end if
         end associate
      end do
      if (law%law == LAW_ROUGH) then
         if (.not. law_constants_fit(law, nu_pair, line, file, errors)) return
         call convert_interface(law, nu_pair)
         ! the reversal pressures for which the unloading branch is admissible (the reader
         ! rejects the laws whose range does not start at 0: M2 < M, or CN2 > CN with M2 = M)
         call admissible_reversals(law%cn, law%m, law%cn2, law%m2, p_lo, law%p_reversal_max)
      else
         allocate (law%r_t(size(nu_pair)))
         law%r_t = 1.0_dp
      end if
   end subroutine define_law

   !> Whether the constants of a rough law in model units, c_n, c_n2 and R,
   !! are finite and positive with finite reciprocals (the springs divide by
   !! them).  The unit conversion raises the pressure factor f to the power m
   !! (c_n = 1e-3 c_n,in f^m, eq. 2.1a in model units), which over- or
   !! underflows for an exponent out of any physical range (NORMAL 1.0 99999):
   !! checked on logarithms before anything is computed, and reported as an
   !! input error at the interface's line.
   !! Ref: Altenbach & Buczkowski, eqs. (2.1a), (2.8); SPEC §2.4.
   logical function law_constants_fit(law, nu_pair, line, file, errors) result(fit)
      type(interface_t), intent(in) :: law          !! constants as given (the *_in fields)
      real(dp), intent(in) :: nu_pair(:)            !! Poisson's ratio of each pair [-]
      integer, intent(in) :: line                   !! deck line of the interface
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      real(dp) :: lf, ll, s_in, r_lo, r_hi
      fit = .true.
      ! a missing NORMAL card or a non-positive constant: the reader has reported it (its
      ! logarithm would be -infinity, a floating-point trap in a checked build)
      if (.not. (law%cn_in > 0.0_dp .and. law%cn2_in > 0.0_dp .and. law%m_in > 0.0_dp .and. &
                 law%m2_in > 0.0_dp)) then
         fit = .false.
         return
      end if
      if (law%r_given .and. .not. law%r_in > 0.0_dp) then
         fit = .false.
         return
      end if
      select case (law%units)
      case (UNITS_KGF_UM)
         lf = log(KGF_PER_NMM2)
         ll = log(1.0e-3_dp)
      case (UNITS_N_UM)
         lf = 0.0_dp
         ll = log(1.0e-3_dp)
      case default
         lf = 0.0_dp
         ll = 0.0_dp
      end select
      ! the factors f^m, f^m2, f^(1-S) on their own, then the constants
      call check('NORMAL', 'the unit factor f^M', law%m_in*lf)
      call check('NORMAL', 'the unit factor f^M2', law%m2_in*lf)
      call check('NORMAL', 'CN in model units', ll + log(law%cn_in) + law%m_in*lf)
      call check('NORMAL', 'CN2 in model units', ll + log(law%cn2_in) + law%m2_in*lf)
      s_in = law%s_in
      if (.not. law%s_given) s_in = 1.0_dp - law%m_in
      if (law%r_given) then
         r_lo = log(law%r_in)
         r_hi = r_lo
      else if (size(nu_pair) > 0) then
         ! eq. (2.8): R = 2 c_n m (1 + nu)
         r_lo = log(2.0_dp*law%m_in) + log(law%cn_in) + log(1.0_dp + minval(nu_pair))
         r_hi = log(2.0_dp*law%m_in) + log(law%cn_in) + log(1.0_dp + maxval(nu_pair))
      else
         return
      end if
      call check('TANGENT', 'the unit factor f^(1-S)', (1.0_dp - s_in)*lf)
      call check('TANGENT', 'R in the deck''s units', r_lo)
      call check('TANGENT', 'R in the deck''s units', r_hi)
      call check('TANGENT', 'R in model units', ll + r_lo + (1.0_dp - s_in)*lf)
      call check('TANGENT', 'R in model units', ll + r_hi + (1.0_dp - s_in)*lf)
   contains
      subroutine check(card, name, lx)
         character(len=*), intent(in) :: card, name
         real(dp), intent(in) :: lx        !! natural logarithm of the constant in model units
         if (.not. fit) return
         if (lx > log(tiny(1.0_dp)) + 1.0_dp .and. lx < log(huge(1.0_dp)) - 1.0_dp) return
         call errors%add('E-CONTACT', 'CONTACT/'//card//': '//name//' would be e^'//rtoa(lx)// &
                         ', beyond the range of the arithmetic: the constant or its exponent is &
                         &out of range '// &
                         '(the unit conversion raises the pressure factor to the exponent)', &
                         file=file, line=line)
         fit = .false.
      end subroutine check
   end function law_constants_fit

   !> Checks across the pairs of all interfaces: a pair joins two bodies and
   !! two different nodes, a node of B partners one node of A, every pair off
   !! the axis has an area, no node is on both sides; an initial penetration
   !! is a warning.
   subroutine check_pairs(m, pairs, size_model, file, errors, warnings)
      type(model_t), intent(in) :: m
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: size_model      !! model size [length]: penetration
                                              !! below 1e-9 of it is none
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      type(error_list_t), intent(inout) :: warnings
      integer, allocatable :: body(:), nolinks(:, :)
      logical :: used_b(m%npoin), master(m%npoin)
      integer :: k, q, nbody
      integer, allocatable :: npen(:), kpen(:)        !! per interface: pairs penetrated, the first
      real(dp), allocatable :: gpen(:, :)            !! per interface: their least and largest g0

      allocate (body(m%npoin), nolinks(2, 0))
      call find_bodies(m, nolinks, body, nbody)
      q = 0
      if (size(pairs) > 0) q = maxval(pairs%iface)
      allocate (npen(q), kpen(q), gpen(2, q))
      npen = 0
      kpen = 0
      gpen(1, :) = huge(1.0_dp)
      gpen(2, :) = -huge(1.0_dp)
      used_b = .false.
      master = .false.
      do k = 1, size(pairs)
         associate (p => pairs(k))
            if (p%kind /= PAIR_RIGID) then
               if (body(p%node_a) == body(p%nodes(2))) then
                  call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'// &
                                  itoa(p%node_b)// &
                                  ': both nodes belong to the same body (a contact spring joins &
                                  &two bodies)', &
                                  file=file, line=p%line)
               end if
               master(p%nodes(2:p%nn)) = .true.
            end if
            if (p%node_a == p%node_b) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'// &
                               itoa(p%node_b)// &
                               ' joins a node to itself', file=file, line=p%line)
            end if
            if (p%kind == PAIR_NODE) then
               if (used_b(p%node_b)) then
                  call errors%add('E-CONTACT', 'CONTACT: node '//itoa(p%node_b)// &
                                  ' of surface B is the partner of '// &
                                  'two nodes of surface A (overlapping surfaces or a too large &
                                  &tolerance)', &
                                  file=file, line=p%line)
               end if
               used_b(p%node_b) = .true.
            end if
            q = p%node_b
            if (p%kind /= PAIR_NODE) q = p%node_a
            if (p%area <= 0.0_dp .and. .not. (m%ntype == NTYPE_AXISYMMETRIC .and. &
                                              m%coord(1, q) <= 1.0e-12_dp*size_model)) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'// &
                               itoa(p%node_b)// &
                               ' has no contact area (its node is on no edge of the paired zone of &
                               &surface '// &
                               merge('B', 'A', p%kind == PAIR_NODE)//')', file=file, line=p%line)
            end if
            if (p%g0 < -1.0e-9_dp*size_model) then
               ! one warning per interface (an interference fit penetrates at every pair)
               if (npen(p%iface) == 0) kpen(p%iface) = k
               npen(p%iface) = npen(p%iface) + 1
               gpen(1, p%iface) = min(gpen(1, p%iface), p%g0)
               gpen(2, p%iface) = max(gpen(2, p%iface), p%g0)
            end if
         end associate
      end do
      do q = 1, size(npen)
         if (npen(q) == 0) cycle
         associate (p => pairs(kpen(q)))
            if (npen(q) == 1) then
               call warnings%add('W-PENETRATION', 'CONTACT: pair '//itoa(p%node_a)//'-'// &
                                 itoa(p%node_b)//' starts with a negative gap (penetration) '// &
                                 rtoa(p%g0), file=file, line=p%line)
            else
               call warnings%add('W-PENETRATION', 'CONTACT: '//itoa(npen(q))//' pairs of '// &
                                 'interface '//itoa(q)//' start with a negative gap '// &
                                 '(penetration) from '//rtoa(gpen(1, q))//' to '// &
                                 rtoa(gpen(2, q))//', the first pair '//itoa(p%node_a)//'-'// &
                                 itoa(p%node_b)//' (an interference, pressed out in the '// &
                                 'first increment)', file=file, line=p%line)
            end if
         end associate
      end do
      do k = 1, size(pairs)
         if (.not. master(pairs(k)%node_a)) cycle
         call errors%add('E-CONTACT', 'CONTACT: node '//itoa(pairs(k)%node_a)// &
                         ' is on surface A and on '// &
                         'surface B (overlapping surfaces)', file=file, line=pairs(k)%line)
      end do
   end subroutine check_pairs

   !> Young's modulus and Poisson's ratio at every node: those of the first
   !! element containing it (0 for a node of no element, e.g. a rigid body's
   !! reference node).
   pure subroutine node_modulus(m, e, nu)
      type(model_t), intent(in) :: m
      real(dp), intent(out) :: e(:)      !! (npoin) Young's modulus [stress]
      real(dp), intent(out) :: nu(:)     !! (npoin) Poisson's ratio [-]
      integer :: ie, k
      logical :: seen(m%npoin)
      seen = .false.
      e = 0.0_dp
      nu = 0.0_dp
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            if (seen(m%lnods(k, ie))) cycle
            seen(m%lnods(k, ie)) = .true.
            e(m%lnods(k, ie)) = m%mats(m%matno(ie))%young
            nu(m%lnods(k, ie)) = m%mats(m%matno(ie))%poiss
         end do
      end do
   end subroutine node_modulus
end module contact_definition
