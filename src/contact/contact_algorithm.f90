!> State determination of the contact springs: the paper's incremental
!! algorithm (section 4; SPEC §4) with the options of SPEC §4.5.
!!
!! Every pair carries a committed state (end of the last increment) and, within
!! an increment, a *mode*: open or closed, virgin or unloading branch, and the
!! tangential state stick / plastic (hardening branch) / slip, with the spring
!! stiffnesses used for the solve.  After each solve `evaluate_pairs` computes
!! the pair forces for the displacement increment from the start of the
!! increment, checks the modes in the order of SPEC §4.3 (open/closed,
!! loading/unloading, tangential), and flags changes; the driver then repeats
!! the increment with the new stiffnesses ("die neue FE-Analyse wird fuer das
!! gegebene Lastinkrement wiederholt").  Force updates:
!!
!! * EXPLICIT (the paper, eqs. 4.9-4.14, SPEC D7): F = F_prev + K dU, with K
!!   from the previous increment (secant from the start pressure p_m in the
!!   first increment, eqs. 4.1-4.6; tangent eq. 4.10 afterwards);
!! * RETURN: the normal force is returned to the curve, F_n = A p(u_n), and
!!   the increment is repeated with the current tangent until the
!!   out-of-balance force vanishes (equilibrium on the curve).
!!
!! Slip (eq. 4.16, 4.18) uses the return-to-cone form of SPEC §4.3: F_T =
!! s mu F_n with K_T = 0, s the sign of the elastic trial force (RETURN: a pair
!! whose iterates cycle between tangential states takes the secant of the law
!! instead, see tangential_return).  The friction
!! coefficient of increment i comes from the effective slip after increment
!! i-1 (explicit, SPEC §2.3).
!!
!! Ideal contact (`LAW IDEAL`, the paper's reference [2]: no roughness,
!! Coulomb friction) on the same pairs: Signorini's conditions
!!     u_n <= 0,  F_n >= 0,  F_n u_n = 0      (u_n the closure = penetration)
!! and Coulomb's law per increment, |F_T| <= mu F_n with du_T = 0 (stick) or
!! F_T = mu F_n sign(du_T) (slip), enforced by an augmented Lagrangian
!! (Uzawa) method: with multipliers lam_n, lam_T and penalty stiffnesses
!! eps_n, eps_T a pair carries
!!     F_n = max(0, lam_n + eps_n u_n),   F_T = proj_[-mu F_n, mu F_n](lam_T + eps_T du_T),
!! its mode (open / closed-stick / closed-slip) is found by the same repeats as
!! the rough springs (an active-set iteration on the linear penalised problem),
!! and once the modes settle and the bodies balance the multipliers are updated,
!! lam <- F, until the penetration |u_n| of every closed pair and the slip
!! |du_T| of every sticking pair are below AUGMENTED TOL (1e-6) times the
!! smallest contact element length.  The penalty only sets the speed of this
!! iteration, not the answer: eps_n = FACTOR E* A^ / h per pair, the
!! stiffness of a layer of the bodies' contact modulus E* and thickness h/FACTOR
!! (FACTOR = 100, h the contact element length, A^ the pair's share of the
!! element areas), and eps_T = eps_n / FACTOR; the system stays symmetric
!! positive definite.  Within one Uzawa iterate the slip bound is mu lam_n
!! (Tresca's law, linear modes) until the penetrations and stick slips are
!! within tolerance; then it is mu F_n of the current normal force (Coulomb's
!! law, the coupling corrected by the out-of-balance force), so that converged
!! slipping pairs carry mu F_n to 1e-10.  A closed pair keeps a tension within
!! a band (half its start force or multiplier) while the multipliers drive it
!! to zero, and opens when they do not: a body held by contact alone that is
!! unloaded to zero rests closed at zero force instead of floating free.
!! Ref: J. C. Simo, T. A. Laursen, An augmented Lagrangian treatment of contact
!! problems involving friction, Comput. Struct. 42 (1992) 97-116; P. Wriggers,
!! Computational Contact Mechanics (2006), ch. 6.
module contact_algorithm
   use kinds, only: dp
   use contact_types, only: contact_def_t, interface_t, contact_pair_t, LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, &
                            UPDATE_RETURN, SLIP_GROSS, MAX_PAIR_NODES, NEWCLOSED_TANGENT
   use contact_laws, only: virgin_pressure, virgin_closure, virgin_tangent, unloading_tangent, residual_closure, &
                           normal_pressure, normal_tangent, tangential_stiffness, friction_coefficient, &
                           bilinear_return, unloading_constant
   use contact_element, only: pair_stiffness, pair_kinematics, pair_forces
   use roundoff, only: roundoff_floor
   ! the state codes are those of the contact fields record (model layer)
   use records, only: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   implicit none
   private

   public :: pair_state_t, pair_mode_t, contact_state_t
   public :: contact_init, begin_increment, pair_matrix, evaluate_pairs, commit_increment, &
             pair_force_vector, law_drift, check_invariants, augment_multipliers, pair_dofs, &
             start_force_normal, frozen_pairs, tangential_drift, drop_regularisation, regularise_slip
   public :: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   public :: MAX_SWITCH

   !> Mode changes of one rough pair within one increment; a pair that reaches
   !! it keeps its last mode for the rest of the increment (frozen: chatter).
   integer, parameter :: MAX_SWITCH = 6

   !> RETURN: lower bound of the secant tangential stiffness of a pair whose iterates
   !! cycle between tangential states, as a fraction of K_T^e (about the branch slope
   !! kappa = 0.04-0.05): a slipping pair keeps a stiffness that damps the cycle.
   real(dp), parameter :: KSEC_LOW = 0.05_dp
   !> Ideal law: the regularising tangential spring of a slipping pair in the
   !! matrix, relative to eps_T (set_kt_ideal).
   real(dp), parameter :: KT_SLIP_REG = 1.0e-6_dp
   !> Ideal law: changes of a pair's tangential mode within one increment after
   !! which its mode no longer changes the matrix (evaluate_ideal): a cycle.  With
   !! 6 or 8 the unloading to zero of tests/decks/robust_ideal/punch_2_20_mu02,
   !! whose modes settle slowly at vanishing forces, took 54 solutions instead of 33.
   integer, parameter :: IDEAL_TSWITCH = 10

   !> Committed state of one pair (end of an increment).
   type :: pair_state_t
      logical :: closed = .false.
      logical :: on_unloading = .false.   !! on the unloading/reloading branch through A
      real(dp) :: ua = 0.0_dp, pa = 0.0_dp  !! reversal point A (closure, pressure)
      real(dp) :: un = 0.0_dp             !! total closure (u_b - u_a).n - g0
      real(dp) :: ut = 0.0_dp             !! total tangential displacement (u_a - u_b).t
      real(dp) :: fn = 0.0_dp, ft = 0.0_dp  !! spring forces
      real(dp) :: utp = 0.0_dp            !! irreversible tangential displacement (SPEC §2.3 a)
      real(dp) :: utp_gross = 0.0_dp      !! gross-slip part only (SPEC §2.3 b)
      real(dp) :: ve = 0.0_dp             !! effective slip, path length of the chosen definition
      real(dp) :: xb = 0.0_dp             !! back force: centre of the elastic band |F_T - xb| <= 0.625 mu F_n
      real(dp) :: fy = 0.0_dp             !! EXPLICIT: largest |F_T| reached on the hardening branch or in slip
      integer :: tstate = TS_STICK
      real(dp) :: mu = 0.0_dp             !! friction coefficient used in the increment
      real(dp) :: kn = 0.0_dp, kt = 0.0_dp  !! spring stiffnesses of the increment
   end type pair_state_t

   !> The assumption for one pair within an increment.
   type :: pair_mode_t
      logical :: closed = .false.
      logical :: newly_closed = .false.
      logical :: held = .false.           !! RETURN: held at the zero-force point instead of opening
      logical :: touching = .false.       !! RETURN: at the zero-force point of its branch to round-off
                                          !! (touching_band) in the last evaluation
      logical :: on_unloading = .false.
      real(dp) :: ua = 0.0_dp, pa = 0.0_dp
      integer :: tstate = TS_STICK
      integer :: tsign = 0                !! direction (+-1) of the branch or slip of tstate (0: stick)
      real(dp) :: xb = 0.0_dp             !! back force of the tangential law after the increment
      real(dp) :: kn = 0.0_dp             !! normal spring stiffness for the solve
      real(dp) :: kte = 0.0_dp            !! elastic tangential spring stiffness of the increment
      real(dp) :: kt = 0.0_dp             !! tangential spring stiffness for the solve
      real(dp) :: uthr = 0.0_dp           !! closure at which the pair (re)closes
      real(dp) :: mu = 0.0_dp
      integer :: nswitch = 0              !! mode changes in the increment so far (see MAX_SWITCH)
      integer :: tvisited = 0             !! RETURN: the tangential states (tstate, tsign) met in the
                                          !! increment, one bit each (tstate_bit)
      logical :: tstable = .false.        !! RETURN: back in a state met before: the secant stiffness of
                                          !! the law over the increment from then on (tangential_return)
      real(dp) :: sdir = 0.0_dp           !! ideal law: direction (+-1) of the current slip
      logical :: released = .false.       !! ideal law: kept closed in tension until the multipliers
                                          !! settled, then let open (no tension band any more)
      logical :: hold = .false.           !! ideal law: the multipliers were just updated; the
                                          !! next evaluation keeps the modes (see augment_multipliers)
      integer :: tswitch = 0              !! ideal law: changes of the tangential mode in the increment
      logical :: tfixed = .false.         !! ideal law: the tangential mode cycled (IDEAL_TSWITCH changes);
                                          !! the secant stiffness ksec in the matrix from then on (evaluate_ideal)
      real(dp) :: ksec = 0.0_dp           !! ideal law, tfixed: secant of the projection over du_T
   end type pair_mode_t

   type :: contact_state_t
      type(pair_state_t), allocatable :: s(:)     !! committed
      type(pair_mode_t), allocatable :: md(:)     !! current modes
      real(dp), allocatable :: fn(:), ft(:)       !! current forces
      real(dp), allocatable :: dun(:), dut(:)     !! current increments of closure and slip
      real(dp) :: p_start = 0.0_dp                !! p_m of eq. (4.1)
      real(dp) :: p_incr = 0.0_dp                 !! RETURN: pressure the increment is expected to bring
                                                  !! (contact_start's increment_pressure; 0: none)
      logical :: chatter = .false.                !! a pair exhausted its mode changes
      logical :: regularise = .true.              !! RETURN: a pair slipping at vanishing normal force keeps
                                                  !! K_T^e (vanishing_slip_kt) until drop_regularisation
      logical :: regularise_slip = .false.        !! RETURN: every closed pair in slip keeps K_T^e (regularise_slip:
                                                  !! the system was singular without)
      ! ideal contact (augmented Lagrangian)
      logical :: has_ideal = .false.              !! some interface is IDEAL
      logical :: has_rough = .false.              !! some interface is ROUGH
      real(dp), allocatable :: lam_n(:), lam_t(:) !! multipliers of the current Uzawa iterate
      real(dp), allocatable :: eps_n(:), eps_t(:) !! penalty stiffnesses [force/length]
      real(dp) :: tol_pen = 0.0_dp                !! accepted penetration and stick slip [length]
      real(dp) :: violation = 0.0_dp              !! largest penetration / stick slip at the last check
      integer :: augmentations = 0                !! multiplier updates in the current increment
      real(dp) :: fref = 0.0_dp                   !! largest normal force of an ideal pair committed so far
      logical :: coulomb = .false.                !! the slip bound is mu F_n (else mu lam_n) in this increment
   end type contact_state_t

contains

   !> Initial states: closure -g0; closed if the gap is within tolerance (or
   !! among the n_start smallest gaps).  Penalty stiffnesses and tolerance of
   !! the ideal law.
   subroutine contact_init(cdef, gap_tol, st)
      type(contact_def_t), intent(in) :: cdef
      real(dp), intent(in) :: gap_tol
      type(contact_state_t), intent(out) :: st
      integer :: np, j, k, nclose
      integer :: order(size(cdef%pairs))
      real(dp) :: g(size(cdef%pairs)), hmin
      np = size(cdef%pairs)
      allocate (st%s(np), st%md(np), st%fn(np), st%ft(np), st%dun(np), st%dut(np))
      allocate (st%lam_n(np), st%lam_t(np), st%eps_n(np), st%eps_t(np))
      st%fn = 0.0_dp
      st%ft = 0.0_dp
      st%dun = 0.0_dp
      st%dut = 0.0_dp
      st%lam_n = 0.0_dp
      st%lam_t = 0.0_dp
      st%eps_n = 0.0_dp
      hmin = huge(1.0_dp)
      do j = 1, np
         st%s(j)%un = -cdef%pairs(j)%g0
         st%s(j)%closed = cdef%pairs(j)%g0 <= gap_tol .and. active(cdef, j)
         st%s(j)%mu = friction_coefficient(cdef%ifaces(cdef%pairs(j)%iface), 0.0_dp)
         if (is_ideal(cdef, j)) then
            st%has_ideal = .true.
            associate (pr => cdef%pairs(j))
               if (pr%length > 0.0_dp .and. pr%estar > 0.0_dp) then
                  st%eps_n(j) = cdef%opts%aug_factor*pr%estar*max(pr%share, pr%area)/pr%length
               end if
               if (pr%length > 0.0_dp) hmin = min(hmin, pr%length)
            end associate
         else
            st%has_rough = .true.
         end if
      end do
      if (st%has_ideal) then
         ! a pair without scales (made in code) takes the stiffest of the others
         where (st%eps_n <= 0.0_dp) st%eps_n = max(maxval(st%eps_n), 1.0_dp)
         st%tol_pen = cdef%opts%aug_tol*hmin
      end if
      ! tangentially a softer penalty (a layer of thickness h, not h/FACTOR): the
      ! trial force of a sticking pair, lam_T + eps_T du_T, must not swing across
      ! the whole friction cone for a tiny du_T, or the stick/slip modes chatter
      st%eps_t = st%eps_n/cdef%opts%aug_factor
      if (cdef%opts%n_start > 0) then
         ! the n_start pairs of smallest gap start closed (paper, example 5.2)
         g = cdef%pairs%g0
         order = [(j, j=1, np)]
         do j = 2, np
            k = j
            do while (k > 1)
               if (g(order(k - 1)) <= g(order(k))) exit
               order(k - 1:k) = order(k:k - 1:-1)
               k = k - 1
            end do
         end do
         nclose = 0
         st%s%closed = .false.
         do k = 1, np
            if (nclose >= cdef%opts%n_start) exit
            if (.not. active(cdef, order(k))) cycle
            st%s(order(k))%closed = .true.
            nclose = nclose + 1
         end do
      end if
   end subroutine contact_init

   !> Normal force of pair j at the start of an increment, after
   !! begin_increment: the committed force, except for an ideal pair that
   !! starts closed, whose force in its mode is lam_n + eps_n u_n (the
   !! penalty term of its current closure, a tension when it starts closed
   !! across an open gap, START NSTART).  The driver puts the difference into
   !! the first right-hand side, so the first solution already closes such
   !! gaps instead of finding every start pair open and the body unsupported.
   pure real(dp) function start_force_normal(cdef, st, j) result(fn)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: j
      fn = st%s(j)%fn
      if (is_ideal(cdef, j) .and. st%md(j)%closed) fn = st%lam_n(j) + st%eps_n(j)*st%s(j)%un
   end function start_force_normal

   !> Does pair j obey the ideal law?
   pure logical function is_ideal(cdef, j)
      type(contact_def_t), intent(in) :: cdef
      integer, intent(in) :: j
      is_ideal = cdef%ifaces(cdef%pairs(j)%iface)%law == LAW_IDEAL
   end function is_ideal

   !> Can pair j carry force?  A rough spring needs an area; an ideal
   !! constraint does not (the node on the axis of a quadratic axisymmetric
   !! edge has zero lumped area but must not penetrate either).
   pure logical function active(cdef, j)
      type(contact_def_t), intent(in) :: cdef
      integer, intent(in) :: j
      active = cdef%pairs(j)%area > 0.0_dp .or. is_ideal(cdef, j)
   end function active

   !> The 2 nn dof values (u_a, u_2, ..., u_nn) of a pair from a nodal field
   !! (2, npoin); zero beyond 2 nn.
   pure function pair_dofs(v, pr) result(x)
      real(dp), intent(in) :: v(:, :)
      type(contact_pair_t), intent(in) :: pr
      real(dp) :: x(2*MAX_PAIR_NODES)
      integer :: k
      x = 0.0_dp
      do k = 1, pr%nn
         x(2*k - 1:2*k) = v(:, pr%nodes(k))
      end do
   end function pair_dofs

   !> Modes and stiffnesses for the next increment from the committed states.
   !! In the first increment closed pairs get the secants of eqs. (4.5), (4.6)
   !! at the start pressure p_m; later the tangents of eqs. (4.10), (4.11).
   !! Ideal pairs keep their committed modes, get the penalty stiffnesses and
   !! start the Uzawa iteration from their committed forces.
   pure subroutine begin_increment(cdef, st, first)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: first
      integer :: j
      real(dp) :: p, pfloor
      logical :: returning
      pfloor = cdef%opts%p_min_ratio*st%p_start
      returning = cdef%opts%update == UPDATE_RETURN
      st%augmentations = 0
      st%violation = 0.0_dp
      st%coulomb = .false.
      st%regularise = .true.
      st%regularise_slip = .false.
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            md = pair_mode_t()
            ! the forces and increments of the last evaluation are those of the start
            st%fn(j) = s%fn
            st%ft(j) = s%ft
            st%dun(j) = 0.0_dp
            st%dut(j) = 0.0_dp
            if (ifc%law == LAW_IDEAL) then
               md%closed = s%closed
               md%mu = friction_coefficient(ifc, s%ve)
               md%tstate = merge(s%tstate, TS_STICK, s%closed)
               if (md%tstate == TS_SLIP) md%sdir = sign(1.0_dp, s%ft)
               md%kte = st%eps_t(j)
               if (md%closed) md%kn = st%eps_n(j)
               call set_kt_ideal(ifc, md)
               st%lam_n(j) = s%fn
               st%lam_t(j) = s%ft
               cycle
            end if
            md%closed = s%closed
            md%on_unloading = s%on_unloading
            md%ua = s%ua
            md%pa = s%pa
            md%tstate = s%tstate
            md%mu = friction_coefficient(ifc, s%ve)
            md%uthr = reclose_threshold(ifc, s%on_unloading, s%ua, s%pa)
            if (returning .and. .not. first .and. pr%area > 0.0_dp) then
               if (reload_from_zero(ifc, s, md, pr%area, st%p_incr)) then
                  ! a reload from the zero-force end of the unloading branch (its tangent
                  ! is zero there for m2 < 1, and a pair open by a gap the increment
                  ! closes has none): touching, on the secant from the zero-force point to
                  ! the pressure the increment is expected to bring (eq. 4.1's start
                  ! pressure for this increment); the solutions then follow the law
                  md%closed = .true.
                  md%newly_closed = .not. s%closed
                  p = st%p_incr
                  md%kn = pr%area*p/max(branch_closure(ifc, md, p) - md%uthr, tiny(1.0_dp))
                  md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(local_index(cdef, j)))
                  md%xb = merge(s%xb, 0.0_dp, s%closed)
                  md%tstate = TS_STICK
                  md%tsign = 0
                  call set_kt(ifc, md)
                  cycle
               end if
            end if
            if (.not. s%closed .or. pr%area <= 0.0_dp) then
               md%closed = .false.
               md%tstate = TS_STICK
               cycle
            end if
            if (first) then
               md%kn = pr%area*st%p_start**(1.0_dp - ifc%m)/ifc%cn
               p = st%p_start
            else
               p = max(s%fn/pr%area, pfloor)
               if (s%on_unloading) then
                  md%kn = pr%area*unloading_tangent(p, unloading_constant(s%ua, s%pa, ifc%cn2, ifc%m2), ifc%m2)
               else
                  md%kn = pr%area*virgin_tangent(p, ifc%cn, ifc%m)
               end if
            end if
            md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(local_index(cdef, j)))
            md%xb = s%xb
            md%tstate = TS_STICK
            md%tsign = 0
            if (.not. returning) then
               ! EXPLICIT: the tangential state follows the committed forces and the new mu
               if (s%tstate == TS_SLIP .and. abs(s%ft) >= md%mu*s%fn*(1.0_dp - 1.0e-9_dp)) then
                  md%tstate = TS_SLIP
               else if (ifc%hardening .and. s%tstate /= TS_STICK .and. &
                        abs(s%ft) >= max(0.625_dp*md%mu*s%fn, s%fy)*(1.0_dp - 1.0e-9_dp)) then
                  md%tstate = TS_PLASTIC
               end if
            end if
            ! RETURN: every increment starts from the elastic (stick) stiffness and the
            ! return mapping finds the state; starting a reversal with the branch slope
            ! (or K_T = 0 in slip) would move a force-driven pair 1/kappa times too far
            call set_kt(ifc, md)
         end associate
      end do
   end subroutine begin_increment

   !> Does a rough pair start a loading increment (expected pressure pe > 0)
   !! at the zero-force end of its unloading branch?  Closed there with zero
   !! force (to 1e-9 of its force at A), or open below its residual closure
   !! u_res by less than the closure pe brings on the branch (a gap the
   !! increment is expected to close; after an unloading to zero these are the
   !! differences of the pairs' residual closures, down to round-off).
   pure logical function reload_from_zero(ifc, s, md, area, pe) result(yes)
      type(interface_t), intent(in) :: ifc
      type(pair_state_t), intent(in) :: s
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: area, pe
      yes = .false.
      if (.not. (pe > 0.0_dp) .or. .not. s%on_unloading .or. ifc%law /= LAW_ROUGH) return
      if (s%closed) then
         yes = s%fn <= 1.0e-9_dp*area*s%pa
      else
         yes = s%un >= md%uthr - (branch_closure(ifc, md, pe) - md%uthr)
      end if
   end function reload_from_zero

   !> The band around the zero-force point u_thr of a pair's unloading branch in
   !! which the pair counts as touching at the point (RETURN): from
   !! u_thr - eps^max(1, m2) t to u_thr + eps^m2 t (t = u_A - u_thr the branch's
   !! travel, eps = 1e-9); `above` selects the half-width above the point.  On the
   !! branch, (u - u_thr)/t = (p/p_A)^m2, so throughout the band the law's force is
   !! at most eps A p_A, round-off of the pair's force scale, whatever m2; below the
   !! point so is the touching spring's, A p_A (u - u_thr)/t, and a touching pair
   !! carries it.  Above it, on a convex branch (m2 < 1), the band is wider than
   !! that: from eps t to eps^m2 t a touching pair carries the law's force with the
   !! spring's stiffness.  The chord stiffness of the branch vanishes with the
   !! force there (as (u - u_thr)^(1/m2 - 1)), and a body resting on such a pair
   !! alone is placed by Newton only to the round-off of its forces over that
   !! stiffness, not to the correction tolerance (TOLU); the spring's stiffness
   !! places it to the round-off over the spring's.
   pure real(dp) function touching_band(ifc, md, above) result(b)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(in) :: md
      logical, intent(in) :: above
      real(dp), parameter :: eps = 1.0e-9_dp
      if (above) then
         b = eps**ifc%m2*max(md%ua - md%uthr, 0.0_dp)
      else
         b = eps**max(1.0_dp, ifc%m2)*max(md%ua - md%uthr, 0.0_dp)
      end if
   end function touching_band

   !> Closure at which an open pair closes: 0, or the residual closure after unloading.
   pure real(dp) function reclose_threshold(ifc, on_unloading, ua, pa) result(u)
      type(interface_t), intent(in) :: ifc
      logical, intent(in) :: on_unloading
      real(dp), intent(in) :: ua, pa
      u = 0.0_dp
      if (on_unloading) u = max(residual_closure(ua, pa, ifc%cn2, ifc%m2), 0.0_dp)
   end function reclose_threshold

   !> Closure at pressure p on the branch a pair of mode md follows: the
   !! unloading/reloading branch through its reversal point while p < p_A, the
   !! virgin curve otherwise (inverse of normal_pressure).
   pure real(dp) function branch_closure(ifc, md, p) result(u)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: p
      if (md%on_unloading .and. p < md%pa) then
         u = md%ua - unloading_constant(md%ua, md%pa, ifc%cn2, ifc%m2)*(md%pa**ifc%m2 - p**ifc%m2)
      else
         u = virgin_closure(p, ifc%cn, ifc%m)
      end if
   end function branch_closure

   !> Position of pair j among the pairs of its interface (for per-pair R).
   pure integer function local_index(cdef, j) result(k)
      type(contact_def_t), intent(in) :: cdef
      integer, intent(in) :: j
      integer :: i
      k = 0
      do i = 1, j
         if (cdef%pairs(i)%iface == cdef%pairs(j)%iface) k = k + 1
      end do
   end function local_index

   !> Tangential spring stiffness of a mode: K_T^e, kappa K_T^e or 0 (eq. 4.17).
   pure subroutine set_kt(ifc, md)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(inout) :: md
      if (ifc%friction == FRICTION_NONE .or. .not. md%closed) then
         md%kt = 0.0_dp
         return
      end if
      if (md%tstable) then
         ! (a cycling pair: tangential_return sets its secant; K_T^e until it does)
         md%kt = md%kte
         return
      end if
      select case (md%tstate)
      case (TS_STICK)
         md%kt = md%kte
      case (TS_PLASTIC)
         md%kt = ifc%kappa*md%kte
      case default
         md%kt = 0.0_dp
      end select
   end subroutine set_kt

   !> Global (2 nn) x (2 nn) matrix of pair j in its current mode (eq. 3.31),
   !! in the leading part of ke (the rest is zero).
   pure subroutine pair_matrix(cdef, st, j, ke)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: j
      real(dp), intent(out) :: ke(:, :)       !! (2 MAX_PAIR_NODES, 2 MAX_PAIR_NODES)
      associate (pr => cdef%pairs(j))
         call pair_stiffness(pr%t, pr%n, pr%nn, pr%w, st%md(j)%kt, st%md(j)%kn, ke)
      end associate
   end subroutine pair_matrix

   !> Internal-force vector (r_a, r_2, ..., r_nn) of pair j for forces fn, ft.
   pure subroutine pair_force_vector(cdef, j, fn, ft, r)
      type(contact_def_t), intent(in) :: cdef
      integer, intent(in) :: j
      real(dp), intent(in) :: fn, ft
      real(dp), intent(out) :: r(:)           !! (2 MAX_PAIR_NODES)
      associate (pr => cdef%pairs(j))
         call pair_forces(pr%t, pr%n, pr%nn, pr%w, fn, ft, r)
      end associate
   end subroutine pair_force_vector

   !> Forces of every pair for the displacement increment du (from the start of
   !! the increment), with the mode checks of SPEC §4.3.  `changed(j)` tells
   !! that pair j changed its mode (the increment must be repeated).
   pure subroutine evaluate_pairs(cdef, st, du, changed, first)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: du(:, :)          !! (2, npoin) displacement increments
      logical, intent(out) :: changed(:)
      logical, intent(in) :: first              !! first increment (secant iteration option)
      integer :: j
      real(dp) :: dun, dut, u, fn, ft, p, pfloor, pold, fpred, utol
      logical :: returning, may_switch, held_now

      returning = cdef%opts%update == UPDATE_RETURN
      pfloor = cdef%opts%p_min_ratio*st%p_start
      changed = .false.
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            call pair_kinematics(pr%t, pr%n, pr%nn, pr%w, pair_dofs(du, pr), dun, dut)
            ! the normal force the last solution predicted for this pair (its linearisation)
            fpred = st%fn(j) + md%kn*(dun - st%dun(j))
            st%dun(j) = dun
            st%dut(j) = dut
            if (ifc%law == LAW_IDEAL) then
               call evaluate_ideal(cdef, st, j, changed(j))
               cycle
            end if
            u = s%un + dun
            may_switch = md%nswitch < MAX_SWITCH
            held_now = .false.
            md%touching = .false.
            fn = 0.0_dp
            ft = 0.0_dp
            if (pr%area <= 0.0_dp) then
               st%fn(j) = 0.0_dp
               st%ft(j) = 0.0_dp
               cycle
            end if
            ! RETURN: a closure within round-off of the zero-force point of the branch
            ! is that point (closed, F_n = 0), not a lift-off
            utol = 0.0_dp
            if (returning) utol = 1.0e-9_dp*max(abs(s%un), abs(u), abs(md%ua - md%uthr))

            ! 1. open / closed (SPEC D5)
            if (.not. md%closed) then
               if (u > md%uthr .and. may_switch) then
                  md%closed = .true.
                  md%newly_closed = .true.
                  ! the secant of its penetration; below the floor pressure, the secant to the
                  ! floor point of its branch (p_min over the penetration itself would grow
                  ! without bound as the penetration found by the trial solve goes to zero)
                  p = normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, md%ua, md%pa)
                  if (cdef%opts%newly_closed == NEWCLOSED_TANGENT) then
                     ! option: the tangent of the virgin curve at the floor pressure
                     p = max(p, pfloor)
                     md%kn = pr%area*virgin_tangent(p, ifc%cn, ifc%m)
                  else if (p >= pfloor) then
                     md%kn = pr%area*p/max(u - md%uthr, tiny(1.0_dp))
                  else
                     p = pfloor
                     md%kn = pr%area*p/max(branch_closure(ifc, md, p) - md%uthr, tiny(1.0_dp))
                  end if
                  md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(local_index(cdef, j)))
                  md%tstate = TS_STICK
                  md%tsign = 0
                  md%xb = 0.0_dp
                  call set_kt(ifc, md)
                  call flag(changed(j), md%nswitch, st%chatter)
               end if
            end if
            if (md%closed) then
               if (returning) then
                  fn = pr%area*normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, md%ua, md%pa)
               else if (md%newly_closed) then
                  fn = md%kn*(u - md%uthr)
               else
                  fn = s%fn + md%kn*dun
               end if
               if (returning .and. md%on_unloading .and. s%closed .and. .not. md%newly_closed .and. &
                   u - md%uthr <= touching_band(ifc, md, st%regularise_slip) .and. &
                   md%uthr - u <= touching_band(ifc, md, .false.)) then
                  ! RETURN, at the zero-force point of its unloading branch to round-off, on either
                  ! side (touching_band): touching there, on the secant from A to the point,
                  ! K (u - u_thr), which the next solution settles; no change of state.  The
                  ! branch's own stiffness is singular at the point (zero for m2 < 1, infinite
                  ! for m2 > 1): Newton on it cannot carry the out-of-balance force that the
                  ! round-off of a solution leaves on a body held by such pairs (1e-9 of the
                  ! increment's force for a stiff block on soft pairs), and stalls.  The
                  ! committed force is the law's at the final closure (commit_increment).
                  ! Above the point beyond the spring's band (m2 < 1: eps t < u - u_thr <=
                  ! eps^m2 t) the pair keeps the law's force, at most eps A p_A, with the
                  ! spring's stiffness: the vanishing chord would place a body resting on it
                  ! only to the round-off of its forces over that chord; the spring's force
                  ! there could be balanced by the tension of a pair held below its point
                  ! (up to 1e-6 A p_A), which the committed forces would not be
                  md%touching = .true.
                  held_now = .true.
                  md%kn = pr%area*md%pa/max(md%ua - md%uthr, tiny(1.0_dp))
                  if (u - md%uthr <= touching_band(ifc, md, .false.)) fn = md%kn*(u - md%uthr)
               else if (returning .and. ifc%m2 > 1.0_dp .and. u <= md%uthr - utol .and. s%closed .and. s%fn > 0.0_dp .and. &
                   .not. (md%held .or. md%newly_closed) .and. may_switch) then
                  ! RETURN, a loaded pair overshooting its zero-force point (a Newton step on a
                  ! concave branch, m2 > 1): once per increment it is held by the secant from
                  ! its start to that point, K (u - u_thr) <= 0, which the next solution
                  ! brings back to the point; below it a second time, it opens.  On a convex
                  ! branch (m2 <= 1) no such hold: the tangent step stops short of the point
                  ! and the chord lands on it, so a pair the solution drives below it is
                  ! pulled off by the other pairs and opens in that solution, with all the
                  ! others driven through zero (a hold would cost every pair, and so every
                  ! group of pairs opening in turn, one more solution)
                  md%held = .true.
                  held_now = .true.
                  md%kn = s%fn/max(s%un - md%uthr, tiny(1.0_dp))
                  fn = md%kn*(u - md%uthr)
                  call flag(changed(j), md%nswitch, st%chatter)
               else if (returning .and. ifc%m2 <= 1.0_dp .and. md%on_unloading .and. s%closed .and. &
                        u < md%uthr .and. u > md%uthr - 1.0e-6_dp*abs(md%ua - md%uthr)) then
                  ! RETURN, within 1e-6 of the branch's travel below its zero-force point (the
                  ! accuracy of a solution in which the pair is the last support of a body, its
                  ! chord stiffness vanishing): still touching, on the secant from A to the point,
                  ! K (u - u_thr), which the next solution brings back to it; no change of state.
                  ! The force left there is the increment's out-of-balance force (at most the
                  ! residual tolerance); the committed force is clamped at zero
                  md%held = .true.
                  held_now = .true.
                  md%kn = pr%area*md%pa/max(md%ua - md%uthr, tiny(1.0_dp))
                  fn = md%kn*(u - md%uthr)
               else if ((fn < 0.0_dp .or. u <= md%uthr - utol) .and. may_switch) then
                  md%closed = .false.
                  md%newly_closed = .false.
                  md%kn = 0.0_dp
                  md%tstate = TS_STICK
                  md%tsign = 0
                  call set_kt(ifc, md)
                  fn = 0.0_dp
                  call flag(changed(j), md%nswitch, st%chatter)
               end if
            end if

            ! 2. loading / unloading (SPEC §2.1): reversal starts the unloading branch at
            ! A = (u, p(u)) of the committed state, the pressure taken from the law
            if (md%closed .and. s%closed .and. .not. md%newly_closed .and. .not. md%on_unloading .and. &
                dun < 0.0_dp .and. may_switch) then
               md%on_unloading = .true.
               md%ua = s%un
               md%pa = virgin_pressure(s%un, ifc%cn, ifc%m)
               md%uthr = reclose_threshold(ifc, .true., md%ua, md%pa)
               if (.not. returning) then
                  ! the increment is repeated with the unloading tangent; whether the pair
                  ! opens is decided with the displacements of that solution, not these
                  ! (the paper's eq. 4.10: the tangent at the pressure of the previous increment)
                  md%kn = pr%area*unloading_tangent(max(s%fn/pr%area, pfloor), &
                                                    unloading_constant(md%ua, md%pa, ifc%cn2, ifc%m2), ifc%m2)
                  fn = s%fn + md%kn*dun
               else
                  fn = pr%area*normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, .true., md%ua, md%pa)
               end if
               call flag(changed(j), md%nswitch, st%chatter)
            end if

            ! optional secant iteration of the first increment (SPEC §4.1)
            ! (a secant update is no change of state: it does not count as a switch)
            if (first .and. cdef%opts%first_iterate .and. md%closed .and. .not. returning .and. &
                .not. md%newly_closed .and. fn > 0.0_dp) then
               pold = md%kn
               md%kn = pr%area*(fn/pr%area)**(1.0_dp - ifc%m)/ifc%cn
               if (abs(md%kn - pold) > 1.0e-10_dp*pold) then
                  fn = s%fn + md%kn*dun
                  changed(j) = .true.
               end if
            end if

            ! Newton stiffness for the next solve of a RETURN update
            if (returning .and. md%closed .and. .not. held_now) &
               md%kn = newton_normal_stiffness(ifc, md, pr%area, s%fn, st%fn(j), fpred, fn, u, dun)

            ! 3. tangential (SPEC §4.3 item 3 and 4)
            if (md%closed .and. ifc%friction /= FRICTION_NONE) then
               if (returning) then
                  call tangential_return(ifc, s, md, pr%area, dut, fn, may_switch, ft, changed(j), st%chatter)
                  ! the stiffness of the mode (no regularising value left from an earlier
                  ! solution), or the secant tangential_return gave a cycling pair
                  if (.not. md%tstable) call set_kt(ifc, md)
                  if (st%regularise) call vanishing_slip_kt(s, md, fn)
                  if (st%regularise_slip .and. md%tstate == TS_SLIP .and. .not. md%tstable) md%kt = md%kte
               else
                  call tangential_explicit(ifc, s, md, dut, fn, may_switch, ft, changed(j), st%chatter)
               end if
            end if
            st%fn(j) = fn
            st%ft(j) = ft
         end associate
      end do
   end subroutine evaluate_pairs

   !> Normal spring stiffness of a closed rough pair for the next Newton
   !! solution (RETURN): the tangent of its branch at its closure, except
   !! * when the last solution predicted zero (or tensile) force for the pair,
   !!   or, on a convex unloading branch (m2 <= 1), less than half the force the
   !!   law gives now: the chord to the branch's zero-force point,
   !!   A p(u)/(u - u_thr), which ends a pair that unloads to zero force at u_thr
   !!   in one step (the tangent p^(1-m2)/(cn2 m2) vanishes there for m2 < 1, and
   !!   Newton on a root of order 1/m2 only halves the distance per solution for
   !!   m2 = 0.5).  Among pairs of a body unloaded to zero the chord weights the
   !!   pairs of small u_thr most, so that the solutions open the pairs of larger
   !!   u_thr in large groups instead of one by one.  The chord step lands below
   !!   an intermediate target force (the branch is convex), after which the
   !!   prediction exceeds the force and the tangent takes over: no cycling;
   !! * at zero force (tangent zero): the secant over the increment, which
   !!   does not vanish, so that a body held only by such pairs stays regular.
   pure real(dp) function newton_normal_stiffness(ifc, md, area, fn0, fnprev, fpred, fn, u, dun) result(k)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: area     !! lumped area
      real(dp), intent(in) :: fn0      !! committed force (start of the increment)
      real(dp), intent(in) :: fnprev   !! force after the previous solution
      real(dp), intent(in) :: fpred    !! force the previous solution predicted
      real(dp), intent(in) :: fn, u    !! force and closure now
      real(dp), intent(in) :: dun      !! closure increment so far
      real(dp) :: fref, ktan
      ! the force scale of the pair: its forces in this increment and, on the unloading
      ! branch, the force at A (a pair resting at zero force has no other)
      fref = max(fn0, abs(fnprev), fn, tiny(1.0_dp))
      if (md%on_unloading) fref = max(fref, area*md%pa)
      ktan = area*normal_tangent(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, md%ua, md%pa)
      if (fpred <= 0.5_dp*fn .and. fn > 1.0e-12_dp*fref .and. u > md%uthr .and. md%on_unloading .and. ifc%m2 <= 1.0_dp) then
         k = fn/(u - md%uthr)
      else if (fpred <= 1.0e-8_dp*fref .and. fn > 1.0e-12_dp*fref .and. u > md%uthr) then
         k = fn/(u - md%uthr)
      else if (ktan > 0.0_dp .and. fn > 1.0e-12_dp*fref) then
         k = max(ktan, 1.0e-3_dp*fn/max(u - md%uthr, tiny(1.0_dp)))
      else if (abs(dun) > 0.0_dp .and. abs(fn0 - fn) > 1.0e-12_dp*fref) then
         ! (below the zero-force point: the secant to that point)
         k = abs(fn0 - fn)/max(abs(u - dun - max(u, md%uthr)), tiny(1.0_dp))
      else
         ! at rest at zero force: the stiffness of the last solution (the tangent at
         ! the floor pressure from begin_increment)
         k = max(md%kn, area*max(ktan, virgin_tangent(fref/area, ifc%cn, ifc%m)))
      end if
   end function newton_normal_stiffness

   !> RETURN: the tangential law integrated exactly over the increment at the
   !! current normal force (bilinear_return, Masing memory); a new state or a
   !! new direction of the branch or slip is a mode change, and the pair takes
   !! the tangent of the state it lands on (K_T^e, kappa K_T^e, 0).
   !!
   !! Where the law has kinks (the branch start, slip onset) and the normal force
   !! moves with the tangential forces (slip at mu F_n: dF_T/du_n = mu K_n, a term
   !! the symmetric system cannot hold), these tangents can make the iterates cycle:
   !! a pair lands in slip, its K_T = 0 lets the solution throw its F_n (and so its
   !! limit) far off, the return lands on the branch, and back.  A pair that comes
   !! back to a state (tstate, direction) it met before in the increment is taken
   !! off this cycle: from then on it carries the secant of the law over the
   !! increment, K_T = |F_T - F_T0| / |du_T| bounded to [KSEC_LOW K_T^e, K_T^e]
   !! (all slopes of the law lie in [0, K_T^e]: the secant iteration of a monotone
   !! law, which does not jump between the extreme slopes as the tangents do; the
   !! bound keeps a slipping pair from being left free), and its later state changes are no
   !! mode changes: its stiffness no longer depends on its state, and the
   !! out-of-balance force and the last correction decide convergence as for any
   !! Newton step.  The force is always the law's (the return), so a converged
   !! increment is on the law whatever stiffness led there; the secant only costs
   !! the quadratic rate of that pair.  Such a pair changes its mode at most 5
   !! times (4 new states and the return to one), below MAX_SWITCH: only the
   !! normal state (open / closed, branch) can still freeze a pair.
   pure subroutine tangential_return(ifc, s, md, area, dut, fn, may_switch, ft, changed, chatter)
      type(interface_t), intent(in) :: ifc
      type(pair_state_t), intent(in) :: s
      type(pair_mode_t), intent(inout) :: md
      real(dp), intent(in) :: area            !! lumped area of the pair
      real(dp), intent(in) :: dut, fn
      logical, intent(in) :: may_switch
      real(dp), intent(out) :: ft
      logical, intent(inout) :: changed, chatter
      real(dp) :: xb
      integer :: itrial, tsg
      logical :: unloaded
      call bilinear_return(merge(0.0_dp, s%ft, md%newly_closed), dut, md%kte, ifc%kappa, md%mu*max(fn, 0.0_dp), &
                           merge(0.0_dp, s%xb, md%newly_closed), ifc%hardening, ft, xb, itrial)
      md%xb = xb
      tsg = 0
      if (itrial /= TS_STICK) tsg = nint(sign(1.0_dp, ft - xb))
      ! at zero normal force (to round-off of the pair's forces) nothing holds the pair
      ! tangentially: it slips with F_T = 0 in no particular direction
      unloaded = fn <= 1.0e-12_dp*max(s%fn, area*md%pa, tiny(1.0_dp))
      if (unloaded) then
         ft = 0.0_dp
         md%xb = 0.0_dp
         itrial = TS_SLIP
         tsg = 0
      end if
      md%tvisited = ior(md%tvisited, tstate_bit(md%tstate, md%tsign))
      if ((itrial /= md%tstate .or. tsg /= md%tsign) .and. may_switch) then
         md%tstate = itrial
         md%tsign = tsg
         if (.not. md%tstable) then
            ! back in a state met before in this increment: the iterates cycle between
            ! branches; the pair takes its secant stiffness from now on (below)
            md%tstable = iand(md%tvisited, tstate_bit(itrial, tsg)) /= 0 .and. .not. unloaded
            call set_kt(ifc, md)
            ! a pair reaching zero normal force loses its tangential hold with no jump of
            ! force (mu F_n = 0 bounds stick and slip alike): not a change that forces
            ! another solution; the out-of-balance force of the solution decides
            if (.not. unloaded) call flag(changed, md%nswitch, chatter)
         end if
      end if
      if (md%tstable .and. abs(dut) > 0.0_dp) &
         md%kt = min(max(abs(ft - merge(0.0_dp, s%ft, md%newly_closed))/abs(dut), KSEC_LOW*md%kte), md%kte)
   end subroutine tangential_return

   !> The bit of a tangential state (stick; branch -, +; slip -, 0 (unloaded), +) in
   !! pair_mode_t%tvisited.
   pure integer function tstate_bit(tstate, tsign) result(b)
      integer, intent(in) :: tstate, tsign
      b = 2**(3*tstate + tsign + 1)
   end function tstate_bit

   !> The increment has not converged in half its solutions with the regularising
   !! springs of vanishing slip: for the rest of it every pair has the stiffness of
   !! its mode (K_T = 0 in slip), so that a solution can release pairs whose normal
   !! stiffness is far below K_T^e (the regularising springs, carrying no force,
   !! would absorb the step).  `changed` is set when some stiffness changed (the
   !! system is to be factorized again), else left as it is.
   pure subroutine drop_regularisation(cdef, st, changed)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(inout) :: changed
      integer :: j
      real(dp) :: kt0
      if (.not. st%regularise .or. cdef%opts%update /= UPDATE_RETURN) return
      st%regularise = .false.
      do j = 1, size(st%s)
         associate (ifc => cdef%ifaces(cdef%pairs(j)%iface))
            ! (a pair whose tangential states cycle keeps its secant, within [0.05, 1] K_T^e)
            if (ifc%law /= LAW_ROUGH .or. st%md(j)%tstable) cycle
            kt0 = st%md(j)%kt
            call set_kt(ifc, st%md(j))
            if (abs(st%md(j)%kt - kt0) > 0.0_dp) changed = .true.
         end associate
      end do
   end subroutine drop_regularisation

   !> The system of an increment was singular (RETURN, rough pairs): in its next
   !! attempt every closed rough pair in slip keeps K_T^e in the solve, a
   !! regularising spring that carries no force (its F_T stays the law's), and
   !! the springs of vanishing slip are kept throughout (no drop_regularisation).
   !! A body held only by the contact and a restraint against translation (the
   !! top edge of a block held in x) is turned about that edge by the normal
   !! forces of its pairs alone once they slip (K_T = 0): with one pair left
   !! closed, as the load falls to zero and the pairs open one after another,
   !! nothing holds it.  The converged state is the law's all the same (F_T =
   !! mu F_n in slip).  Called after begin_increment.
   pure subroutine regularise_slip(cdef, st)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      if (cdef%opts%update /= UPDATE_RETURN) return
      st%regularise_slip = .true.
      st%regularise = .true.
   end subroutine regularise_slip

   !> K_T of a closed rough pair (set by its mode before), except that a pair slipping on its
   !! unloading branch at a normal force fn of at most 1e-3 of its committed force
   !! (at zero force included: its friction hold vanishing with the load) gets
   !! K_T^e, a regularising spring that carries no force (F_T is the law's, mu F_n
   !! or 0): with K_T = 0 a body held only by such pairs (and one restraint) has no
   !! tangential or rotational support once one of them is left touching.
   pure subroutine vanishing_slip_kt(s, md, fn)
      type(pair_state_t), intent(in) :: s
      type(pair_mode_t), intent(inout) :: md
      real(dp), intent(in) :: fn
      if (md%closed .and. md%tstate == TS_SLIP .and. md%on_unloading .and. fn <= 1.0e-3_dp*s%fn) md%kt = md%kte
   end subroutine vanishing_slip_kt

   !> EXPLICIT (the paper): F_T = F_T,prev + K_T dU_T with the stiffness of the
   !! assumed state for the whole increment (eqs. 4.15-4.18).  The paper's
   !! reading of Bild 2 is kept for reproduction: onto the branch when |F_T|
   !! passes 0.625 mu F_n or, after unloading (BC, elastic), the largest |F_T|
   !! reached on the branch or in slip (fy), in either direction.
   pure subroutine tangential_explicit(ifc, s, md, dut, fn, may_switch, ft, changed, chatter)
      type(interface_t), intent(in) :: ifc
      type(pair_state_t), intent(in) :: s
      type(pair_mode_t), intent(inout) :: md
      real(dp), intent(in) :: dut, fn
      logical, intent(in) :: may_switch
      real(dp), intent(out) :: ft
      logical, intent(inout) :: changed, chatter
      real(dp) :: limit, trial
      limit = md%mu*fn
      select case (md%tstate)
      case (TS_STICK)
         ft = merge(0.0_dp, s%ft, md%newly_closed) + md%kte*dut
         if (ifc%hardening .and. abs(ft) > max(0.625_dp*limit, s%fy)*(1.0_dp + 1.0e-8_dp) .and. may_switch) then
            ! onto the hardening branch: its slope for the whole increment (eq. 4.15, 4.17)
            md%tstate = TS_PLASTIC
            call set_kt(ifc, md)
            ft = merge(0.0_dp, s%ft, md%newly_closed) + md%kt*dut
            call flag(changed, md%nswitch, chatter)
         end if
         if (abs(ft) > limit*(1.0_dp + 1.0e-8_dp) .and. may_switch) then
            md%tstate = TS_SLIP
            call set_kt(ifc, md)
            ft = sign(limit, ft)
            call flag(changed, md%nswitch, chatter)
         end if
      case (TS_PLASTIC)
         ft = s%ft + md%kt*dut
         trial = s%ft + md%kte*dut
         if ((dut*s%ft < 0.0_dp .or. abs(trial) < max(0.625_dp*limit, s%fy)) .and. may_switch) then
            ! unloading along k_T^e (Bild 2, BC), or an elastic trial below the branch
            md%tstate = TS_STICK
            call set_kt(ifc, md)
            ft = trial
            call flag(changed, md%nswitch, chatter)
         else if (abs(ft) > limit*(1.0_dp + 1.0e-8_dp) .and. may_switch) then
            md%tstate = TS_SLIP
            call set_kt(ifc, md)
            ft = sign(limit, ft)
            call flag(changed, md%nswitch, chatter)
         end if
      case default
         trial = merge(0.0_dp, s%ft, md%newly_closed) + md%kte*dut
         if (abs(trial) < limit*(1.0_dp - 1.0e-8_dp) .and. may_switch) then
            md%tstate = TS_STICK       ! back inside the cone: stick again
            call set_kt(ifc, md)
            ft = trial
            call flag(changed, md%nswitch, chatter)
         else
            ft = sign(limit, trial)
         end if
      end select
   end subroutine tangential_explicit

   !> Round-off of the normal forces of ideal pair j: 1e-10 of the largest
   !! normal force of the run so far or of its multiplier.
   pure real(dp) function round_off_force(st, j) result(f)
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: j
      f = 1.0e-10_dp*max(st%fref, abs(st%lam_n(j)))
   end function round_off_force

   !> Forces and modes of an ideal pair for its current multipliers:
   !! F_n = lam_n + eps_n u_n when closed (0 open), F_T = proj(lam_T + eps_T du_T)
   !! onto [-g, g] with the slip bound g = mu lam_n of the same multipliers
   !! (Tresca's law: every mode linear, the system symmetric) or, once
   !! st%coulomb is set, g = mu F_n (Coulomb's law).  Right after a multiplier
   !! update (md%hold) the modes are kept and only the forces follow.
   pure subroutine evaluate_ideal(cdef, st, jp, chg)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      integer, intent(in) :: jp
      logical, intent(inout) :: chg
      real(dp) :: trial_n, trial_t, lim, band, ksec
      integer :: ts
      logical :: now_closed
      associate (s => st%s(jp), md => st%md(jp), ifc => cdef%ifaces(cdef%pairs(jp)%iface))
         trial_n = st%lam_n(jp) + st%eps_n(jp)*(s%un + st%dun(jp))
         ! an open pair closes when its trial force is a compression; a closed one
         ! opens when its trial force is a tension beyond the band: half its
         ! multiplier or its force at the start of the increment (and at least the
         ! round-off of the run's forces).  Within the band it carries the tension
         ! until the multipliers settle: a body held by contact alone that is
         ! unloaded to zero has every pair closed at zero force, its first
         ! penalty forces are of mixed sign (they sum to the zero load), and
         ! opening each pair in tension would leave a search over the pairs
         ! for the one the body rests on, or none (a singular system).  Released
         ! pairs (augment_multipliers: a tension that the multipliers do not drive
         ! to zero) keep the round-off band only.
         band = round_off_force(st, jp)
         if (.not. md%released) band = max(band, 0.5_dp*max(abs(st%lam_n(jp)), s%fn))
         if (md%hold) then
            now_closed = md%closed
         else if (md%closed) then
            now_closed = trial_n > -band
         else
            now_closed = trial_n > 0.0_dp
         end if
         if (now_closed .neqv. md%closed) then
            md%closed = now_closed
            md%newly_closed = now_closed .and. .not. s%closed
            md%tstate = TS_STICK
            chg = .true.
            md%nswitch = md%nswitch + 1
         end if
         st%fn(jp) = merge(trial_n, 0.0_dp, md%closed)
         st%ft(jp) = 0.0_dp
         if (md%closed .and. ifc%friction /= FRICTION_NONE) then
            ! the slip bound: Tresca's mu lam_n (linear modes, one solution per
            ! multiplier update) until the penetrations and stick slips are within
            ! tolerance, then Coulomb's mu F_n of the current normal force
            ! (augment_multipliers sets st%coulomb): a slipping pair then carries
            ! mu F_n at every solution, and the multipliers need not bring
            ! mu lam_n to mu F_n to 1e-10, a linear iteration as slow as the
            ! sticking pairs' soft tangential penalty makes it (86-123 solutions
            ! per increment on a frictional ring of segment pairs).  The matrix
            ! keeps K_T = 0 (symmetric): the coupling mu dF_n is corrected by
            ! the out-of-balance force of the next solutions.
            lim = md%mu*max(merge(st%fn(jp), st%lam_n(jp), st%coulomb), 0.0_dp)
            trial_t = st%lam_t(jp) + st%eps_t(jp)*st%dut(jp)
            ! the cone is widened by the round-off allowance of the Coulomb check
            ! (1e-10 F_n): with lam_n = 0 (the first iterate of a pair closed
            ! without force) the bound is zero, and an exact test would decide
            ! stick or slip, and so the number of repeats, by the sign of the
            ! round-off in du_T of a pair that does not move tangentially
            if (md%hold .and. md%tstate == TS_SLIP) then
               ts = TS_SLIP
               st%ft(jp) = md%sdir*lim
            else if (md%tfixed .and. .not. md%hold) then
               ! a pair whose mode cycled: the projection of the trial force onto the
               ! cone, with the secant stiffness of the projection over du_T in the
               ! matrix (set_kt_ideal; the out-of-balance force corrects the rest)
               if (abs(trial_t) <= lim + 1.0e-10_dp*max(st%fn(jp), 0.0_dp)) then
                  ts = TS_STICK
                  st%ft(jp) = trial_t
                  ksec = st%eps_t(jp)
               else
                  ts = TS_SLIP
                  st%ft(jp) = sign(lim, trial_t)
                  md%sdir = sign(1.0_dp, trial_t)
                  ! (a multiplier outside the cone, |lam_T| > lim, gives no positive secant)
                  ksec = KT_SLIP_REG*st%eps_t(jp)
                  if (abs(trial_t - st%lam_t(jp)) > 0.0_dp) ksec = st%eps_t(jp)* &
                     min(max((st%ft(jp) - st%lam_t(jp))/(trial_t - st%lam_t(jp)), KT_SLIP_REG), 1.0_dp)
               end if
               ! a new factorization when the secant moved by more than 10 %
               if (abs(ksec - md%ksec) > 0.1_dp*md%ksec) then
                  md%ksec = ksec
                  chg = .true.
               end if
            else if (md%hold .or. abs(trial_t) <= lim + 1.0e-10_dp*max(st%fn(jp), 0.0_dp) .or. &
                (md%tstate == TS_SLIP .and. trial_t*md%sdir < 0.0_dp)) then
               ! stick; also a slipping pair whose trial force has turned
               ! against its slip: it sticks first and its stick stiffness
               ! settles the new state (a jump from +g to -g at once, across
               ! the whole cone, makes the active set cycle when the load
               ! reverses after full slip)
               ts = TS_STICK
               st%ft(jp) = trial_t
            else
               ts = TS_SLIP
               st%ft(jp) = sign(lim, trial_t)
               md%sdir = sign(1.0_dp, trial_t)
            end if
            if (ts /= md%tstate) then
               ! (the mode of a tfixed pair no longer changes its stiffness: no repeat)
               if (.not. md%tfixed) then
                  chg = .true.
                  md%nswitch = md%nswitch + 1
                  if (lim > md%mu*round_off_force(st, jp)) md%tswitch = md%tswitch + 1
                  ! an active set that cycles: the stick/slip modes of the pairs at the
                  ! edge of a slip zone can each be wrong for the others' (a slip force
                  ! not in the matrix moves a neighbour back across its cone; a soft
                  ! annulus on a stiff one cycled through 5 mode patterns for 100
                  ! solutions).  From now on the pair's force is the projection and its
                  ! stiffness the secant of it (above); the changes at a zero bound
                  ! (lam_n = 0, a body released at zero load) are not counted
                  md%tfixed = md%tswitch >= IDEAL_TSWITCH
                  md%ksec = st%eps_t(jp)
               end if
               md%tstate = ts
            end if
         end if
         md%kn = merge(st%eps_n(jp), 0.0_dp, md%closed)
         md%kte = st%eps_t(jp)
         md%hold = .false.
         call set_kt_ideal(ifc, md)
      end associate
   end subroutine evaluate_ideal

   !> Tangential stiffness of an ideal pair for the solve: eps_T sticking, and
   !! slipping a regularising spring KT_SLIP_REG eps_T in the matrix only (its
   !! force stays mu F_n: the out-of-balance force of the next solution corrects
   !! the difference).  A body held tangentially by friction alone whose pairs
   !! all slip at once -- every pair of the first iterate of a body pressed
   !! without multipliers (the bound mu lam_n = 0), every pair at zero load --
   !! would otherwise be free to translate (a singular system); with the spring
   !! it stays at rest when the friction forces balance, and it moves on (and
   !! the increment fails, out of balance) when they cannot.
   pure subroutine set_kt_ideal(ifc, md)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(inout) :: md
      call set_kt(ifc, md)
      if (ifc%friction /= FRICTION_NONE .and. md%closed .and. md%tstate == TS_SLIP) md%kt = KT_SLIP_REG*md%kte
      if (ifc%friction /= FRICTION_NONE .and. md%closed .and. md%tfixed) md%kt = md%ksec
   end subroutine set_kt_ideal

   !> Uzawa step of the ideal pairs, called when the modes have settled and the
   !! bodies balance the current forces.  The increment is converged when every
   !! closed ideal pair penetrates by at most tol_pen (|u_n|: penetration, or a
   !! gap under load, the complementarity defect), every sticking one slipped
   !! by at most tol_pen in the increment and is inside Coulomb's cone,
   !! |F_T| <= mu F_n (it sticks within Tresca's bound mu lam_n, and a normal
   !! force that fell in the increment leaves it outside), every slipping one
   !! carries |F_T| = mu F_n and no closed one a tension, all three to 1e-10 of
   !! the largest normal force of the increment or of the run.  Otherwise the multipliers
   !! take the current forces (lam <- F), the next evaluation keeps the modes,
   !! and `done` is false; within tolerance, slipping pairs off mu F_n switch
   !! the slip bound to Coulomb's for the rest of the increment, and pairs in a
   !! tension that does not collapse (it exceeds half the largest multiplier:
   !! not a body coming to rest at zero load) are released to open.
   pure subroutine augment_multipliers(cdef, st, done)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(out) :: done
      integer :: j
      real(dp) :: viol, fmax, coulomb, tension, fabs, lamabs, fround, outside
      viol = 0.0_dp
      outside = 0.0_dp
      coulomb = 0.0_dp
      fmax = 0.0_dp
      tension = 0.0_dp
      fabs = 0.0_dp
      lamabs = 0.0_dp
      do j = 1, size(st%s)
         if (is_ideal(cdef, j)) fmax = max(fmax, st%fn(j))
      end do
      fround = 1.0e-10_dp*max(fmax, st%fref)
      do j = 1, size(st%s)
         if (.not. is_ideal(cdef, j)) cycle
         associate (s => st%s(j), md => st%md(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. md%closed) cycle
            viol = max(viol, abs(s%un + st%dun(j)))
            tension = max(tension, -st%fn(j))
            fabs = max(fabs, abs(st%fn(j)))
            lamabs = max(lamabs, abs(st%lam_n(j)))
            if (ifc%friction /= FRICTION_NONE .and. md%tstate == TS_STICK) then
               viol = max(viol, abs(st%dut(j)))
               ! a sticking pair within Tresca's bound mu lam_n of its multiplier but
               ! beyond Coulomb's mu F_n of its force (the normal force fell in the
               ! increment by less than the penetration tolerance shows): outside
               ! the cone, not converged; the update lam_n <- F_n lowers its bound
               outside = max(outside, abs(st%ft(j)) - md%mu*max(st%fn(j), 0.0_dp))
            end if
            if (ifc%friction /= FRICTION_NONE .and. md%tstate == TS_SLIP) &
               coulomb = max(coulomb, abs(abs(st%ft(j)) - md%mu*st%fn(j)))
         end associate
      end do
      st%violation = viol
      done = viol <= st%tol_pen .and. coulomb <= fround .and. tension <= fround .and. outside <= fround
      if (done) return
      ! within tolerance but slipping pairs off mu F_n: Coulomb's bound from now on
      if (viol <= st%tol_pen .and. coulomb > fround) st%coulomb = .true.
      if (viol <= st%tol_pen .and. tension > fround .and. fabs > 0.5_dp*lamabs) then
         ! closed pairs in tension whose forces the multipliers do not drive to
         ! zero (the forces do not collapse as those of a body at rest under a
         ! zero load do): they open (their band is the round-off from now on)
         do j = 1, size(st%s)
            if (is_ideal(cdef, j) .and. st%md(j)%closed .and. st%fn(j) < -fround) st%md(j)%released = .true.
         end do
      end if
      st%augmentations = st%augmentations + 1
      do j = 1, size(st%s)
         if (.not. is_ideal(cdef, j)) cycle
         st%lam_n(j) = st%fn(j)
         st%lam_t(j) = st%ft(j)
         ! the forces of the new multipliers at the current displacements are not
         ! a test of the modes: a pair's trial force jumps by lam_new - lam_old
         ! until the next solution moves the bodies by the multipliers' change
         ! (e.g. by the whole force lam_old of a pair that is unloaded to zero)
         st%md(j)%hold = .true.
      end do
   end subroutine augment_multipliers

   !> Record a mode change of one pair.
   pure subroutine flag(changed, nswitch, chatter)
      logical, intent(inout) :: changed, chatter
      integer, intent(inout) :: nswitch
      changed = .true.
      nswitch = nswitch + 1
      if (nswitch >= MAX_SWITCH) chatter = .true.
   end subroutine flag

   !> Commit the increment: totals, branch, irreversible slip, effective slip.
   pure subroutine commit_increment(cdef, st)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      integer :: j
      real(dp) :: dutp, ft_old
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            ft_old = s%ft
            s%un = s%un + st%dun(j)
            s%ut = s%ut + st%dut(j)
            s%mu = md%mu
            s%kn = md%kn
            s%kt = md%kt
            if (ifc%law == LAW_IDEAL) then
               ! no elastic layer: all tangential motion of a slipping pair is
               ! irreversible; a sticking one moved by at most tol_pen
               s%closed = md%closed
               ! (a tension left is within the round-off of the run's forces)
               s%fn = merge(max(st%fn(j), 0.0_dp), 0.0_dp, md%closed)
               st%fref = max(st%fref, s%fn)
               s%ft = merge(st%ft(j), 0.0_dp, md%closed)
               s%tstate = merge(md%tstate, TS_STICK, md%closed)
               if (md%closed .and. md%tstate == TS_SLIP .and. ifc%friction /= FRICTION_NONE) then
                  s%utp = s%utp + st%dut(j)
                  s%utp_gross = s%utp_gross + st%dut(j)
                  s%ve = s%ve + abs(st%dut(j))
               end if
               cycle
            end if
            if (md%closed) then
               s%closed = .true.
               s%fn = st%fn(j)
               ! held at the zero-force point of a convex branch: no tension
               if (md%held .and. ifc%m2 <= 1.0_dp) s%fn = max(s%fn, 0.0_dp)
               ! touching at the zero-force point: the law's force there (below round-off)
               if (md%touching) s%fn = pr%area*normal_pressure(s%un, ifc%cn, ifc%m, ifc%cn2, ifc%m2, &
                                                               md%on_unloading, md%ua, md%pa)
               s%ft = st%ft(j)
               ! (and a tangential force within the friction limit of that force)
               if (md%touching) s%ft = sign(min(abs(s%ft), s%mu*max(s%fn, 0.0_dp)), s%ft)
               s%on_unloading = md%on_unloading
               s%ua = md%ua
               s%pa = md%pa
               ! reloading past the reversal point: back on the virgin curve
               if (s%on_unloading .and. s%un >= s%ua) s%on_unloading = .false.
               ! irreversible tangential displacement: all but the elastic part (SPEC §2.3)
               dutp = 0.0_dp
               if (ifc%friction /= FRICTION_NONE .and. md%tstate /= TS_STICK .and. md%kte > 0.0_dp) then
                  dutp = st%dut(j) - (s%ft - merge(0.0_dp, ft_old, md%newly_closed))/md%kte
               end if
               s%utp = s%utp + dutp
               if (md%tstate == TS_SLIP) s%utp_gross = s%utp_gross + dutp
               if (ifc%slip_def == SLIP_GROSS) then
                  if (md%tstate == TS_SLIP) s%ve = s%ve + abs(dutp)
               else
                  s%ve = s%ve + abs(dutp)
               end if
               s%tstate = md%tstate
               if (ifc%friction /= FRICTION_NONE) s%xb = md%xb
               if (md%tstate /= TS_STICK) s%fy = max(s%fy, abs(s%ft))
            else
               s%closed = .false.
               s%xb = 0.0_dp
               s%fy = 0.0_dp
               s%fn = 0.0_dp
               s%ft = 0.0_dp
               s%tstate = TS_STICK
               s%on_unloading = md%on_unloading
               s%ua = md%ua
               s%pa = md%pa
            end if
         end associate
      end do
   end subroutine commit_increment

   !> SPEC §7 invariants of the committed states: no closed pair in tension,
   !! |F_T| <= mu F_n, the effective slip never decreases (`ve_old` is the
   !! previous increment's).  Returns the number of violations and a message
   !! naming the first one; `pairs`, every pair that violates one.
   !! The force checks allow 1e-10 of the largest committed F_n (the
   !! iteration's tolerance) plus the round-off floor of the module roundoff
   !! for the forces that cancel in a pair's force: its committed force is
   !! the sum of the increments that loaded and unloaded it, forces of the
   !! run's scale `fscale` (the largest nodal force so far).  At zero load
   !! F_n is itself round-off, and 1e-10 of it would call round-off a
   !! violation; for ordinary loads the floor is 1e-14 of the forces.  Ideal
   !! pairs are accepted to 1e-10 of the largest normal force of the run so
   !! far (st%fref, augment_multipliers): the iteration's tolerance is of that
   !! force also once the load, and with it every F_n, has gone to zero.
   subroutine check_invariants(st, ve_old, nbad, msg, pairs, fscale)
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: ve_old(:)
      integer, intent(out) :: nbad
      character(len=:), allocatable, intent(out) :: msg
      integer, allocatable, intent(out), optional :: pairs(:)   !! the pairs concerned, ascending
      real(dp), intent(in), optional :: fscale    !! the run's force scale (absent: the largest committed |F_n|)
      real(dp) :: fmax, tol
      integer :: j
      logical :: hit(size(st%s))
      character(len=24) :: b
      nbad = 0
      msg = ''
      hit = .false.
      fmax = maxval([0.0_dp, abs(st%s%fn)])
      tol = 1.0e-10_dp*max(fmax, st%fref) + roundoff_floor(fmax)
      if (present(fscale)) tol = 1.0e-10_dp*max(fmax, st%fref) + roundoff_floor(max(fmax, fscale))
      do j = 1, size(st%s)
         associate (s => st%s(j))
            write (b, '(i0)') j
            if (s%closed .and. s%fn < -tol) call bad('pair '//trim(b)//' is closed with a tensile normal force')
            if (.not. s%closed .and. (abs(s%fn) > 0.0_dp .or. abs(s%ft) > 0.0_dp)) &
               call bad('pair '//trim(b)//' is open but carries a force')
            if (abs(s%ft) > s%mu*max(s%fn, 0.0_dp) + tol) call bad('pair '//trim(b)//' has |F_T| > mu F_n')
            if (s%ve < ve_old(j) - 1.0e-14_dp*max(1.0_dp, ve_old(j))) &
               call bad('pair '//trim(b)//': the effective slip decreased')
         end associate
      end do
      if (present(pairs)) pairs = pack([(j, j=1, size(st%s))], hit)
   contains
      subroutine bad(text)
         character(len=*), intent(in) :: text
         nbad = nbad + 1
         hit(j) = .true.
         if (nbad == 1) msg = text
      end subroutine bad
   end subroutine check_invariants

   !> The rough pairs whose modes were frozen in the current increment: they
   !! changed their modes MAX_SWITCH times and kept the last one (chatter).
   !! Ideal pairs are never frozen (their active set iterates to the end).
   pure function frozen_pairs(cdef, st) result(list)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, allocatable :: list(:)      !! pair numbers, ascending
      integer :: j
      list = pack([(j, j=1, size(st%md))], [(st%md(j)%nswitch >= MAX_SWITCH .and. &
                                             .not. is_ideal(cdef, j), j=1, size(st%md))])
   end function frozen_pairs

   !> Largest departure of a closed pair's normal force from its curve,
   !! |F_n - A p(u_n)| / max F_n: the drift of the explicit scheme (SPEC §4.2).
   pure real(dp) function law_drift(cdef, st) result(drift)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer :: j
      real(dp) :: fmax, f
      drift = 0.0_dp
      fmax = 0.0_dp
      do j = 1, size(st%s)
         if (.not. st%s(j)%closed) cycle
         fmax = max(fmax, st%s(j)%fn)
      end do
      if (fmax <= 0.0_dp) return
      do j = 1, size(st%s)
         associate (s => st%s(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. s%closed .or. ifc%law /= LAW_ROUGH) cycle
            f = pr%area*normal_pressure(s%un, ifc%cn, ifc%m, ifc%cn2, ifc%m2, s%on_unloading, s%ua, s%pa)
            drift = max(drift, abs(s%fn - f)/fmax)
         end associate
      end do
   end function law_drift

   !> Largest departure of a closed rough pair's tangential force from the
   !! tangential law, |F_T - F_T^law| / max(mu F_n): the tangential drift of
   !! the explicit scheme, measured like law_drift's normal one.  F_T^law is
   !! the law integrated along the committed history: every increment, the
   !! return mapping of the law (bilinear_return, Masing's memory; the
   !! increment's elastic stiffness K_T^e and mu) applied to the committed
   !! tangential displacement increment at the committed normal force, from
   !! the law's own force and back force after the last increment (tlaw, kept
   !! by the caller); a pair that opens forgets them, one that closes starts
   !! from zero, one at zero normal force (to 1e-12 of its forces) slips with
   !! F_T = 0 (the rules of tangential_return) and is on the law with any
   !! |F_T| <= mu F_n (a touching pair's force is clamped to that).  The NEWTON update commits
   !! exactly that force (drift 0 to round-off); the paper's explicit scheme
   !! keeps the stiffness of the assumed state for the whole increment and its
   !! own reading of the memory, and drifts.  Call once per committed
   !! increment, after commit_increment (st%md and st%dut still hold the
   !! increment's).
   pure subroutine tangential_drift(cdef, st, tlaw, drift, worst)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      real(dp), allocatable, intent(inout) :: tlaw(:, :)  !! (3, npair) the law's F_T, back force, and F_n
      real(dp), intent(out) :: drift                 !! relative to the largest mu F_n of the closed pairs
      integer, intent(out) :: worst                  !! the pair farthest off (0: none)
      integer :: j, itrial
      real(dp) :: fmax, f0, x0, ft, xb, d, dmax
      if (.not. allocated(tlaw)) then
         allocate (tlaw(3, size(st%s)))
         tlaw = 0.0_dp
      end if
      drift = 0.0_dp
      worst = 0
      fmax = 0.0_dp
      dmax = 0.0_dp
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. s%closed .or. ifc%law /= LAW_ROUGH .or. ifc%friction == FRICTION_NONE) then
               tlaw(:, j) = 0.0_dp
               cycle
            end if
            f0 = merge(0.0_dp, tlaw(1, j), md%newly_closed)
            x0 = merge(0.0_dp, tlaw(2, j), md%newly_closed)
            call bilinear_return(f0, st%dut(j), md%kte, ifc%kappa, md%mu*max(s%fn, 0.0_dp), x0, ifc%hardening, &
                                 ft, xb, itrial)
            d = abs(s%ft - ft)
            if (s%fn <= 1.0e-12_dp*max(tlaw(3, j), pr%area*md%pa, tiny(1.0_dp))) then
               ft = 0.0_dp
               xb = 0.0_dp
               ! at zero normal force to round-off the law holds any |F_T| <= mu F_n (a
               ! touching pair's committed force is clamped there, commit_increment)
               d = max(abs(s%ft) - md%mu*max(s%fn, 0.0_dp), 0.0_dp)
            end if
            tlaw(:, j) = [ft, xb, s%fn]
            fmax = max(fmax, md%mu*s%fn)
            if (d > dmax) then
               dmax = d
               worst = j
            end if
         end associate
      end do
      if (fmax > 0.0_dp) then
         drift = dmax/fmax
      else
         worst = 0
      end if
   end subroutine tangential_drift
end module contact_algorithm
