!> One rough pair: the spring of the paper's incremental algorithm (section 4;
!! SPEC §4) with the options of SPEC §4.5, pair by pair.  Every procedure here
!! works on one pair's committed state (pair_state_t) and mode (pair_mode_t);
!! the loops over the pairs are contact_state's and contact_algorithm's.
!!
!! Within an increment a pair has a *mode*: open or closed, virgin or
!! unloading branch, and the tangential state stick / plastic (hardening
!! branch) / slip, with the spring stiffnesses used for the solve.  After each
!! solve `evaluate_rough_pair` computes the pair's forces for the displacement
!! increment from the start of the increment, checks the modes in the order of
!! SPEC §4.3 (open/closed, loading/unloading, tangential), and flags changes;
!! the driver then repeats the increment with the new stiffnesses ("die neue
!! FE-Analyse wird fuer das gegebene Lastinkrement wiederholt").  Force updates:
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
module contact_rough_pair
   use kinds, only: dp
   use contact_types, only: interface_t, contact_pair_t, contact_options_t, LAW_ROUGH, &
         FRICTION_NONE, &
                            UPDATE_RETURN, SLIP_GROSS, NEWCLOSED_TANGENT
   use contact_laws, only: virgin_pressure, virgin_closure, virgin_tangent, unloading_tangent, &
         residual_closure, &
                           normal_pressure, normal_tangent, tangential_stiffness, &
                           friction_coefficient, &
                           bilinear_return, unloading_constant
   use contact_pair_types, only: pair_state_t, pair_mode_t, MAX_SWITCH, TS_STICK, TS_PLASTIC, &
         TS_SLIP
   implicit none
   private

   public :: rough_outcome_t
   public :: rough_begin, evaluate_rough_pair, rough_commit, set_kt
   ! the parts, public for their unit tests
   public :: newton_normal_stiffness, tangential_return, tangential_explicit, touching_band, &
             reclose_threshold, branch_closure, reload_from_zero

   !> RETURN: lower bound of the secant tangential stiffness of a pair whose iterates
   !! cycle between tangential states, as a fraction of K_T^e (about the branch slope
   !! kappa = 0.04-0.05): a slipping pair keeps a stiffness that damps the cycle.
   real(dp), parameter :: KSEC_LOW = 0.05_dp

   !> What one evaluation of a rough pair gives (evaluate_rough_pair).
   type :: rough_outcome_t
      type(pair_mode_t) :: md             !! the pair's mode after the evaluation
      real(dp) :: fn = 0.0_dp, ft = 0.0_dp  !! its forces
      logical :: changed = .false.        !! its mode changed (the increment is to be repeated)
      logical :: chatter = .false.        !! it exhausted its mode changes (MAX_SWITCH)
   end type rough_outcome_t

contains

   !> The mode and stiffnesses of rough pair (state s) for the next increment.
   !! In the first increment a closed pair gets the secants of eqs. (4.5), (4.6)
   !! at the start pressure p_m; later the tangents of eqs. (4.10), (4.11).
   !! RETURN: a pair that starts a loading increment at the zero-force end of
   !! its unloading branch starts touching (reload_from_zero).  `md` comes in
   !! as pair_mode_t() (begin_increment).
   pure subroutine rough_begin(ifc, pr, kloc, s, md, first, returning, p_start, pfloor, p_incr)
      type(interface_t), intent(in) :: ifc
      type(contact_pair_t), intent(in) :: pr
      integer, intent(in) :: kloc              !! position of the pair in its interface (R)
      type(pair_state_t), intent(in) :: s
      type(pair_mode_t), intent(inout) :: md
      logical, intent(in) :: first, returning
      real(dp), intent(in) :: p_start          !! p_m of eq. (4.1)
      real(dp), intent(in) :: pfloor           !! floor pressure p_min_ratio p_m
      real(dp), intent(in) :: p_incr           !! RETURN: pressure the increment
                                               !! is expected to bring
      real(dp) :: p
         md%closed = s%closed
         md%on_unloading = s%on_unloading
         md%ua = s%ua
         md%pa = s%pa
         md%tstate = s%tstate
         md%mu = friction_coefficient(ifc, s%ve)
         md%uthr = reclose_threshold(ifc, s%on_unloading, s%ua, s%pa)
         if (returning .and. .not. first .and. pr%area > 0.0_dp) then
            if (reload_from_zero(ifc, s, md, pr%area, p_incr)) then
               ! a reload from the zero-force end of the unloading branch (its tangent
               ! is zero there for m2 < 1, and a pair open by a gap the increment
               ! closes has none): touching, on the secant from the zero-force point to
               ! the pressure the increment is expected to bring (eq. 4.1's start
               ! pressure for this increment); the solutions then follow the law
               md%closed = .true.
               md%newly_closed = .not. s%closed
               p = p_incr
               md%kn = pr%area*p/max(branch_closure(ifc, md, p) - md%uthr, tiny(1.0_dp))
               md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(kloc))
               md%xb = merge(s%xb, 0.0_dp, s%closed)
               md%tstate = TS_STICK
               md%tsign = 0
               call set_kt(ifc, md)
               return
            end if
         end if
         if (.not. s%closed .or. pr%area <= 0.0_dp) then
            md%closed = .false.
            md%tstate = TS_STICK
            return
         end if
         if (first) then
            md%kn = pr%area*p_start**(1.0_dp - ifc%m)/ifc%cn
            p = p_start
         else
            p = max(s%fn/pr%area, pfloor)
            if (s%on_unloading) then
               md%kn = pr%area*unloading_tangent(p, &
                                                 unloading_constant(s%ua, s%pa, ifc%cn2, ifc%m2), &
                                                 ifc%m2)
            else
               md%kn = pr%area*virgin_tangent(p, ifc%cn, ifc%m)
            end if
         end if
         md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(kloc))
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
   end subroutine rough_begin

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

   !> Forces and mode of one rough pair for the displacement increment of the
   !! pair (closure dun, slip dut from the start of the increment), with the
   !! mode checks of SPEC §4.3: the pair's mode `md` after the previous solution
   !! in, its new mode, forces and whether the mode changed out.  A pure
   !! function of the pair alone: the loop over the pairs is evaluate_pairs'.
   pure function evaluate_rough_pair(ifc, pr, kloc, opts, s, md_in, dun, dut, fnprev, fpred, &
                                     pfloor, first, &
                                     regularise, regularise_slip) result(r)
      type(interface_t), intent(in) :: ifc
      type(contact_pair_t), intent(in) :: pr
      integer, intent(in) :: kloc              !! position of the pair in its interface (R)
      type(contact_options_t), intent(in) :: opts
      type(pair_state_t), intent(in) :: s      !! committed state (start of the increment)
      type(pair_mode_t), intent(in) :: md_in   !! mode of the last solution
      real(dp), intent(in) :: dun, dut         !! closure and slip increments
      real(dp), intent(in) :: fnprev           !! normal force after the previous solution
      real(dp), intent(in) :: fpred            !! normal force the last solution
                                               !! predicted (its linearisation)
      real(dp), intent(in) :: pfloor           !! floor pressure p_min_ratio p_m
      logical, intent(in) :: first             !! first increment (secant iteration option)
      logical, intent(in) :: regularise        !! contact_state_t%regularise
      logical, intent(in) :: regularise_slip   !! contact_state_t%regularise_slip
      type(rough_outcome_t) :: r
      real(dp) :: u, fn, ft, p, pold, utol
      logical :: returning, may_switch, held_now
      r%md = md_in
      returning = opts%update == UPDATE_RETURN
      associate (md => r%md)
         u = s%un + dun
         may_switch = md%nswitch < MAX_SWITCH
         held_now = .false.
         md%touching = .false.
         fn = 0.0_dp
         ft = 0.0_dp
         if (pr%area <= 0.0_dp) then
            r%fn = 0.0_dp
            r%ft = 0.0_dp
            return
         end if
         ! RETURN: a closure within round-off of the zero-force point of the branch
         ! is that point (closed, F_n = 0), not a lift-off
         utol = 0.0_dp
         if (returning) utol = 1.0e-9_dp*max(abs(s%un), abs(u), abs(md%ua - md%uthr))

         ! 1. open / closed (SPEC D5)
         if (.not. md%closed) then
            if (u > md%uthr .and. may_switch) then
               md%closed = .true.
               ! (RETURN: a pair closed at the start of the increment that an iterate opened
               ! closes again from its committed state: the increment's law starts there;
               ! EXPLICIT keeps the paper's secant of the penetration)
               md%newly_closed = .not. (returning .and. s%closed)
               ! the secant of its penetration; below the floor pressure, the secant to the
               ! floor point of its branch (p_min over the penetration itself would grow
               ! without bound as the penetration found by the trial solve goes to zero)
               p = normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, md%ua, md%pa)
               if (opts%newly_closed == NEWCLOSED_TANGENT) then
                  ! option: the tangent of the virgin curve at the floor pressure
                  p = max(p, pfloor)
                  md%kn = pr%area*virgin_tangent(p, ifc%cn, ifc%m)
               else if (p >= pfloor) then
                  md%kn = pr%area*p/max(u - md%uthr, tiny(1.0_dp))
               else
                  p = pfloor
                  md%kn = pr%area*p/max(branch_closure(ifc, md, p) - md%uthr, tiny(1.0_dp))
               end if
               ! (K_T^e of the pressure at which it closes; one closed at the start keeps the
               ! increment's, from its committed pressure)
               if (md%newly_closed) md%kte = pr%area*tangential_stiffness(p, ifc%s, ifc%r_t(kloc))
               md%tstate = TS_STICK
               md%tsign = 0
               md%xb = 0.0_dp
               call set_kt(ifc, md)
               call flag(r%changed, md%nswitch, r%chatter)
            end if
         end if
         if (md%closed) then
            if (returning) then
               fn = pr%area*normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, &
                                            md%ua, md%pa)
            else if (md%newly_closed) then
               fn = md%kn*(u - md%uthr)
            else
               fn = s%fn + md%kn*dun
            end if
            if (returning .and. md%on_unloading .and. s%closed .and. .not. md%newly_closed .and. &
                u - md%uthr <= touching_band(ifc, md, regularise_slip) .and. &
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
            else if (returning .and. ifc%m2 > 1.0_dp .and. u <= md%uthr - utol .and. s%closed &
                     .and. s%fn > 0.0_dp .and. &
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
               call flag(r%changed, md%nswitch, r%chatter)
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
               call flag(r%changed, md%nswitch, r%chatter)
            end if
         end if

         ! 2. loading / unloading (SPEC §2.1): reversal starts the unloading branch at
         ! A = (u, p(u)) of the committed state, the pressure taken from the law -- of a pair
         ! that carries a force (one that starts penetrated, un = -g0 at zero force, loads)
         if (md%closed .and. s%closed .and. .not. md%newly_closed .and. .not. md%on_unloading &
               .and. s%fn > 0.0_dp .and. dun < 0.0_dp .and. may_switch) then
            md%on_unloading = .true.
            md%ua = s%un
            md%pa = virgin_pressure(s%un, ifc%cn, ifc%m)
            md%uthr = reclose_threshold(ifc, .true., md%ua, md%pa)
            if (.not. returning) then
               ! the increment is repeated with the unloading tangent; whether the pair
               ! opens is decided with the displacements of that solution, not these
               ! (the paper's eq. 4.10: the tangent at the pressure of the previous increment)
               md%kn = pr%area*unloading_tangent(max(s%fn/pr%area, pfloor), &
                                                 unloading_constant(md%ua, md%pa, ifc%cn2, &
                                                                    ifc%m2), ifc%m2)
               fn = s%fn + md%kn*dun
            else
               fn = pr%area*normal_pressure(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, .true., md%ua, md%pa)
            end if
            call flag(r%changed, md%nswitch, r%chatter)
         end if

         ! optional secant iteration of the first increment (SPEC §4.1)
         ! (a secant update is no change of state: it does not count as a switch)
         if (first .and. opts%first_iterate .and. md%closed .and. .not. returning .and. &
             .not. md%newly_closed .and. fn > 0.0_dp) then
            pold = md%kn
            md%kn = pr%area*(fn/pr%area)**(1.0_dp - ifc%m)/ifc%cn
            if (abs(md%kn - pold) > 1.0e-10_dp*pold) then
               fn = s%fn + md%kn*dun
               r%changed = .true.
            end if
         end if

         ! Newton stiffness for the next solve of a RETURN update
         if (returning .and. md%closed .and. .not. held_now) md%kn = &
            newton_normal_stiffness(ifc, md, pr%area, s%fn, fnprev, fpred, fn, u, dun, regularise, &
                                    frozen_below=.not. may_switch .and. u <= md%uthr - utol)

         ! 3. tangential (SPEC §4.3 item 3 and 4)
         if (md%closed .and. ifc%friction /= FRICTION_NONE) then
            if (returning) then
               call tangential_return(ifc, s, md, pr%area, dut, fn, may_switch, ft, r%changed, &
                                      r%chatter)
               ! the stiffness of the mode (no regularising value left from an earlier
               ! solution), or the secant tangential_return gave a cycling pair
               if (.not. md%tstable) call set_kt(ifc, md)
               if (regularise) call vanishing_slip_kt(s, md, fn)
               if (regularise_slip .and. md%tstate == TS_SLIP .and. .not. md%tstable) md%kt = md%kte
            else
               call tangential_explicit(ifc, s, md, dut, fn, may_switch, ft, r%changed, r%chatter)
            end if
         end if
         r%fn = fn
         r%ft = ft
      end associate
   end function evaluate_rough_pair

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
   !!   does not vanish, so that a body held only by such pairs stays regular;
   !! * except on a steep unloading branch (m2 < 0.5): "below 1e-12 of the force
   !!   scale" is not "at the zero-force point" there.  The branch gives
   !!   F = A p_A ((u - u_thr)/(u_A - u_thr))^(1/m2), so 1e-12 of A p_A is reached
   !!   (1e-12)^m2 of the travel above the point: 1e-6 for m2 = 0.5, but 1.6e-2
   !!   for m2 = 0.15 (the m of measured surfaces).  A pair that far above its
   !!   point, held by the secant of the increment or of its last solution, makes
   !!   the matrix carry forces its law does not give (a re-closed pair at 1e-16 N
   !!   with 1.3e8 N/mm whose equilibrium force was 16 N; the last loaded pairs of
   !!   a block unloaded to zero could not unload through a neighbour at 1e-15 N
   !!   held by the increment's secant): Newton stalls.  Such a pair (further than
   !!   1e-6 of the travel above its point, the bound where the two definitions
   !!   agree) takes the chord to the point when the last solution sent it towards
   !!   zero force (the exact step for a pair unloading to zero); otherwise it keeps
   !!   the secant while the regularising stiffnesses are kept (`regularise`: a
   !!   body resting on such pairs at zero load is placed by it, as before), and its
   !!   tangent once half the solutions are spent (drop_regularisation).  A
   !!   stiffness below 1e-12 of the branch's mean stiffness A p_A/(u_A - u_thr)
   !!   is raised to 1e-9 of it (the system's pivot test is 1e-12 of the
   !!   diagonal: a body resting on such a pair alone stays regular).
   pure real(dp) function newton_normal_stiffness(ifc, md, area, fn0, fnprev, fpred, fn, u, dun, &
                                                  regularise, frozen_below) result(k)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: area     !! lumped area
      real(dp), intent(in) :: fn0      !! committed force (start of the increment)
      real(dp), intent(in) :: fnprev   !! force after the previous solution
      real(dp), intent(in) :: fpred    !! force the previous solution predicted
      real(dp), intent(in) :: fn, u    !! force and closure now
      real(dp), intent(in) :: dun      !! closure increment so far
      logical, intent(in) :: regularise  !! contact_state_t%regularise: before half the solutions
      logical, intent(in), optional :: frozen_below  !! frozen closed (MAX_SWITCH) below u_thr
      real(dp) :: fref, ktan, kmean
      if (present(frozen_below)) then
         if (frozen_below .and. md%on_unloading .and. md%ua > md%uthr) then
            ! frozen closed by the guard against chatter, below its zero-force point: its law
            ! gives zero force there whatever the closure, so its stiffness is zero, raised to
            ! 1e-9 of the branch's mean stiffness (regularity, as below); a stiffness the law
            ! does not have would carry forces in the solve that the pair never gives
            k = 1.0e-9_dp*area*md%pa/(md%ua - md%uthr)
            return
         end if
      end if
      ! the force scale of the pair: its forces in this increment and, on the unloading
      ! branch, the force at A (a pair resting at zero force has no other)
      fref = max(fn0, abs(fnprev), fn, tiny(1.0_dp))
      if (md%on_unloading) fref = max(fref, area*md%pa)
      ktan = area*normal_tangent(u, ifc%cn, ifc%m, ifc%cn2, ifc%m2, md%on_unloading, md%ua, md%pa)
      if (fpred <= 0.5_dp*fn .and. fn > 1.0e-12_dp*fref .and. u > md%uthr .and. md%on_unloading &
            .and. ifc%m2 <= 1.0_dp) then
         k = fn/(u - md%uthr)
      else if (fpred <= 1.0e-8_dp*fref .and. fn > 1.0e-12_dp*fref .and. u > md%uthr) then
         k = fn/(u - md%uthr)
      else if (ktan > 0.0_dp .and. fn > 1.0e-12_dp*fref) then
         k = max(ktan, 1.0e-3_dp*fn/max(u - md%uthr, tiny(1.0_dp)))
      else if ((fpred <= 0.5_dp*fn .or. .not. regularise) .and. md%on_unloading .and. &
               ifc%m2 < 0.5_dp .and. fn > 0.0_dp .and. &
               u - md%uthr > 1.0e-6_dp*(md%ua - md%uthr)) then
         ! a steep branch (m2 < 0.5): below 1e-12 of its force scale but further than 1e-6 of
         ! its travel above the zero-force point, so not at rest there: the chord to the
         ! point where the last solution sent it towards zero force; its tangent once half
         ! the solutions are spent (no more regularising stiffnesses); a stiffness below
         ! 1e-12 of the branch's mean A p_A/(u_A - u_thr) is raised to 1e-9 of it
         kmean = area*md%pa/max(md%ua - md%uthr, tiny(1.0_dp))
         k = fn/(u - md%uthr)
         if (.not. (fpred <= 0.5_dp*fn)) k = ktan
         if (k < 1.0e-12_dp*kmean) k = max(k, 1.0e-9_dp*kmean)
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
      call bilinear_return(merge(0.0_dp, s%ft, md%newly_closed), dut, md%kte, ifc%kappa, &
                           md%mu*max(fn, 0.0_dp), &
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
      ! (a pair on its secant follows the law's state without a mode change: also when frozen)
      if ((itrial /= md%tstate .or. tsg /= md%tsign) .and. (may_switch .or. md%tstable)) then
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
      if (md%tstable .and. abs(dut) > 0.0_dp) then
         md%kt = min(max(abs(ft - merge(0.0_dp, s%ft, md%newly_closed))/abs(dut), &
                         KSEC_LOW*md%kte), md%kte)
      end if
   end subroutine tangential_return

   !> The bit of a tangential state (stick; branch -, +; slip -, 0 (unloaded), +) in
   !! pair_mode_t%tvisited.
   pure integer function tstate_bit(tstate, tsign) result(b)
      integer, intent(in) :: tstate, tsign
      b = 2**(3*tstate + tsign + 1)
   end function tstate_bit

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
      if (md%closed .and. md%tstate == TS_SLIP .and. md%on_unloading .and. fn <= 1.0e-3_dp*s%fn) &
            then
         md%kt = md%kte
      end if
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
         if (ifc%hardening .and. abs(ft) > max(0.625_dp*limit, s%fy)*(1.0_dp + 1.0e-8_dp) .and. &
               may_switch) then
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

   !> Record a mode change of one pair.
   pure subroutine flag(changed, nswitch, chatter)
      logical, intent(inout) :: changed, chatter
      integer, intent(inout) :: nswitch
      changed = .true.
      nswitch = nswitch + 1
      if (nswitch >= MAX_SWITCH) chatter = .true.
   end subroutine flag

   !> Commit rough pair (state s) at the end of the increment: its forces fn,
   !! ft, branch, irreversible slip and effective slip (SPEC §2.3).  The totals
   !! (closure, slip, mu, stiffnesses) are commit_increment's; ft_old is the
   !! committed F_T before the increment, dut the increment's slip.
   pure subroutine rough_commit(ifc, pr, md, fn, ft, ft_old, dut, s)
      type(interface_t), intent(in) :: ifc
      type(contact_pair_t), intent(in) :: pr
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: fn, ft, ft_old, dut
      type(pair_state_t), intent(inout) :: s
      real(dp) :: dutp
         if (md%closed) then
            s%closed = .true.
            s%fn = fn
            ! held at the zero-force point of a convex branch: no tension
            if (md%held .and. ifc%m2 <= 1.0_dp) s%fn = max(s%fn, 0.0_dp)
            ! touching at the zero-force point: the law's force there (below round-off)
            if (md%touching) s%fn = pr%area*normal_pressure(s%un, ifc%cn, ifc%m, ifc%cn2, ifc%m2, &
                                                            md%on_unloading, md%ua, md%pa)
            s%ft = ft
            ! (and a tangential force within the friction limit of that force)
            if (md%touching) s%ft = sign(min(abs(s%ft), s%mu*max(s%fn, 0.0_dp)), s%ft)
            s%on_unloading = md%on_unloading
            s%ua = md%ua
            s%pa = md%pa
            ! reloading past the reversal point: back on the virgin curve
            if (s%on_unloading .and. s%un >= s%ua) s%on_unloading = .false.
            ! irreversible tangential displacement: all but the elastic part (SPEC §2.3)
            dutp = 0.0_dp
            if (ifc%friction /= FRICTION_NONE .and. md%tstate /= TS_STICK .and. md%kte > 0.0_dp) &
                  then
               dutp = dut - (s%ft - merge(0.0_dp, ft_old, md%newly_closed))/md%kte
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
   end subroutine rough_commit
end module contact_rough_pair
