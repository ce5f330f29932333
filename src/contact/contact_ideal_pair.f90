!> The ideal pairs (`LAW IDEAL`, the paper's reference [2]: no roughness,
!! Coulomb friction) on the same pairs as the rough springs: Signorini's conditions
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
!! element areas), and eps_T = eps_n / sqrt(FACTOR); the system stays symmetric
!! positive definite.  Multipliers that cannot end the increment are updated
!! before the bodies balance their forces to 1e-10, once the out-of-balance
!! force is small against the update (inexact Uzawa, early_update).  Within
!! one Uzawa iterate the slip bound is mu lam_n
!! (Tresca's law, linear modes; Coulomb's mu F_n for a pair without a normal
!! multiplier yet, whose Tresca bound would be zero: without_multiplier) until
!! the penetrations and stick slips are within tolerance; then it is mu F_n
!! of the current normal force (Coulomb's law, the coupling corrected by the
!! out-of-balance force), so that converged slipping pairs carry mu F_n to
!! 1e-10.  A closed pair keeps a tension within a band (half its start force or
!! multiplier) while the multipliers drive it to zero, and opens when they do
!! not: a body held by contact alone that is unloaded to zero rests closed at
!! zero force instead of floating free.
!! Ref: J. C. Simo, T. A. Laursen, An augmented Lagrangian treatment of contact
!! problems involving friction, Comput. Struct. 42 (1992) 97-116; P. Wriggers,
!! Computational Contact Mechanics (2006), ch. 6.
!! The penalties are set by contact_init, the loops over the ideal pairs are
!! contact_state's and contact_algorithm's (the lists st%ideal).
module contact_ideal_pair
   use kinds, only: dp
   use contact_types, only: contact_def_t, interface_t, FRICTION_NONE
   use contact_laws, only: friction_coefficient
   use contact_pair_types, only: pair_state_t, pair_mode_t, contact_state_t, TS_STICK, TS_SLIP
   implicit none
   private

   public :: ideal_begin, evaluate_ideal, set_kt_ideal, augment_multipliers, ideal_commit, &
             early_update

   !> Ideal law: the regularising tangential spring of a slipping pair in the
   !! matrix, relative to eps_T (set_kt_ideal).
   real(dp), parameter :: KT_SLIP_REG = 1.0e-6_dp
   !> Ideal law: changes of a pair's tangential mode within one increment after
   !! which its mode no longer changes the matrix (evaluate_ideal): a cycle.  With
   !! 6 or 8 the unloading to zero of tests/decks/robust_ideal/punch_2_20_mu02,
   !! whose modes settle slowly at vanishing forces, took 54 solutions instead of 33.
   integer, parameter :: IDEAL_TSWITCH = 10
   !> Ideal law: an out-of-balance force below this share of the multipliers'
   !! next change allows their update (early_update).
   real(dp), parameter :: UZAWA_INEXACT = 1.0e-2_dp

   !> The ideal pairs' distance from a converged increment (ideal_defects).
   type :: ideal_defects_t
      real(dp) :: viol = 0.0_dp, coulomb = 0.0_dp, tension = 0.0_dp, outside = 0.0_dp
      real(dp) :: fabs = 0.0_dp, lamabs = 0.0_dp, fround = 0.0_dp, step = 0.0_dp
   end type ideal_defects_t

contains

   !> The mode of ideal pair j for the next increment: its committed mode, the
   !! penalty stiffnesses, and the Uzawa iteration started from its committed
   !! forces.  `md` comes in as pair_mode_t() (begin_increment).
   pure subroutine ideal_begin(ifc, s, eps_n, eps_t, md, lam_n, lam_t)
      type(interface_t), intent(in) :: ifc
      type(pair_state_t), intent(in) :: s
      real(dp), intent(in) :: eps_n, eps_t     !! the pair's penalty stiffnesses
      type(pair_mode_t), intent(inout) :: md
      real(dp), intent(out) :: lam_n, lam_t    !! the pair's multipliers
      md%closed = s%closed
      md%mu = friction_coefficient(ifc, s%ve)
      md%tstate = merge(s%tstate, TS_STICK, s%closed)
      if (md%tstate == TS_SLIP) md%sdir = sign(1.0_dp, s%ft)
      md%kte = eps_t
      if (md%closed) md%kn = eps_n
      call set_kt_ideal(ifc, md)
      lam_n = s%fn
      lam_t = s%ft
   end subroutine ideal_begin

   !> Round-off of the normal forces of ideal pair j: 1e-10 of the largest
   !! normal force of the run so far or of its multiplier.
   pure real(dp) function round_off_force(st, j) result(f)
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: j
      f = 1.0e-10_dp*max(st%fref, abs(st%lam_n(j)))
   end function round_off_force

   !> Whether ideal pair j has no normal multiplier yet (lam_n <= 0): a pair closed
   !! in this increment from a gap or from zero force -- every pair of a first
   !! increment, a pair closing later -- or an interference (a shrink fit's pairs,
   !! penetrated at the start), before the first update of the multipliers.
   !! Tresca's bound mu lam_n of such a pair is zero whatever its normal force, so
   !! the first iterate is frictionless: it slipped every pair of a fit and the
   !! regularising springs alone held a hub against its push (it ran hundreds of
   !! millimetres down the shaft), and it let a bolt head slide 20 um over a plate
   !! clamped by a preload of 1000 N/mm (every head pair slipping at zero friction);
   !! the first update then put mu lam_n on all of them at once, in the directions
   !! of that free slip, the next solution threw the plates' rough interface
   !! (p ~ u^3 of a measured surface) far into compression and back, and its pairs
   !! froze in their modes (tests/decks/newuser/bolt_lap_measured_law).  Such a
   !! pair's bound is Coulomb's mu F_n of its trial normal force instead, until
   !! the multipliers carry its force.
   pure logical function without_multiplier(st, j) result(none)
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: j
      none = st%lam_n(j) <= 0.0_dp
   end function without_multiplier

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
            ! the out-of-balance force of the next solutions.  A pair without a
            ! normal multiplier has Coulomb's bound from the start (without_multiplier).
            lim = md%mu*max(merge(st%fn(jp), st%lam_n(jp), st%coulomb .or. &
                                  without_multiplier(st, jp)), 0.0_dp)
            trial_t = st%lam_t(jp) + st%eps_t(jp)*st%dut(jp)
            ! the cone is widened by the round-off allowance of the Coulomb check
            ! (1e-10 F_n): with a bound of zero (a pair closed at zero normal
            ! force) an exact test would decide stick or slip, and so the number
            ! of repeats, by the sign of the round-off in du_T of a pair that does
            ! not move tangentially
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
                     min(max((st%ft(jp) - st%lam_t(jp))/(trial_t - st%lam_t(jp)), KT_SLIP_REG), &
                         1.0_dp)
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
   !! all slip at once -- every pair at zero load, or (until this version) every
   !! pair of the first iterate of a body pressed without multipliers --
   !! would otherwise be free to translate (a singular system); with the spring
   !! it stays at rest when the friction forces balance, and it moves on (and
   !! the increment fails, out of balance) when they cannot.  A pair whose mode
   !! cycled (tfixed) has the secant ksec of its projection.  (An ideal pair is
   !! never on a hardening branch: stick or slip only.)
   pure subroutine set_kt_ideal(ifc, md)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(inout) :: md
      if (ifc%friction == FRICTION_NONE .or. .not. md%closed) then
         md%kt = 0.0_dp
      else if (md%tfixed) then
         md%kt = md%ksec
      else if (md%tstate == TS_SLIP) then
         md%kt = KT_SLIP_REG*md%kte
      else
         md%kt = md%kte
      end if
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
   pure subroutine augment_multipliers(cdef, st, done, early)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(out) :: done
      !> an update before the bodies balance the forces (early_update): no pair
      !! is released on its tension, which may be the imbalance's
      logical, intent(in), optional :: early
      integer :: j, k
      type(ideal_defects_t) :: d
      real(dp) :: viol, coulomb, tension, fabs, lamabs, fround, outside
      call ideal_defects(cdef, st, d)
      viol = d%viol
      coulomb = d%coulomb
      tension = d%tension
      fabs = d%fabs
      lamabs = d%lamabs
      fround = d%fround
      outside = d%outside
      st%violation = viol
      done = viol <= st%tol_pen .and. coulomb <= fround .and. tension <= fround .and. outside <= &
            fround
      if (done) return
      ! within tolerance but slipping pairs off mu F_n: Coulomb's bound from now on
      if (viol <= st%tol_pen .and. coulomb > fround) st%coulomb = .true.
      if (viol <= st%tol_pen .and. tension > fround .and. fabs > 0.5_dp*lamabs .and. &
          .not. present(early)) then
         ! closed pairs in tension whose forces the multipliers do not drive to
         ! zero (the forces do not collapse as those of a body at rest under a
         ! zero load do): they open (their band is the round-off from now on)
         do k = 1, size(st%ideal)
            j = st%ideal(k)
            if (st%md(j)%closed .and. st%fn(j) < -fround) st%md(j)%released = .true.
         end do
      end if
      st%augmentations = st%augmentations + 1
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         st%lam_n(j) = st%fn(j)
         st%lam_t(j) = st%ft(j)
         ! the forces of the new multipliers at the current displacements are not
         ! a test of the modes: a pair's trial force jumps by lam_new - lam_old
         ! until the next solution moves the bodies by the multipliers' change
         ! (e.g. by the whole force lam_old of a pair that is unloaded to zero)
         st%md(j)%hold = .true.
      end do
   end subroutine augment_multipliers

   !> Inexact Uzawa: whether the multipliers may be updated before the bodies
   !! balance the forces of the current ones to TOLR.  True when a closed ideal
   !! pair still penetrates or slips beyond the tolerance (the increment cannot
   !! end with these multipliers) and the out-of-balance force fbal is below
   !! UZAWA_INEXACT times the update's largest change of a pair's force,
   !! max |F - lam|: the next multipliers are then as good as those of the
   !! balanced forces.  A balance to 1e-10 at every update took 8-10 solutions
   !! an update where the slip bound is Coulomb's (the coupling mu dF_n is
   !! corrected by the out-of-balance force at about 0.08 a solution).  The
   !! increment still ends only on the balanced forces (augment_multipliers).
   pure logical function early_update(cdef, st, fbal)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: fbal              !! the out-of-balance force
      type(ideal_defects_t) :: d
      call ideal_defects(cdef, st, d)
      early_update = (d%viol > st%tol_pen .or. d%tension > d%fround .or. d%outside > d%fround) &
                     .and. fbal <= UZAWA_INEXACT*d%step
   end function early_update

   !> How far the ideal pairs are from the converged increment at the current
   !! forces (augment_multipliers, early_update): the largest penetration or
   !! gap of a closed pair and stick slip (viol), the largest |F_T| - mu F_n of
   !! a sticking pair (outside) and ||F_T| - mu F_n| of a slipping one
   !! (coulomb), the largest tension (tension), the round-off allowance of the
   !! forces (fround: 1e-10 of the largest normal force of the increment or of
   !! the run), and the largest change of a pair's force an update of the
   !! multipliers makes, max |F - lam| (step).
   pure subroutine ideal_defects(cdef, st, d)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      type(ideal_defects_t), intent(out) :: d
      integer :: j, k
      real(dp) :: fmax
      fmax = 0.0_dp
      do k = 1, size(st%ideal)
         fmax = max(fmax, st%fn(st%ideal(k)))
      end do
      d%fround = 1.0e-10_dp*max(fmax, st%fref)
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         associate (s => st%s(j), md => st%md(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. md%closed) cycle
            d%viol = max(d%viol, abs(s%un + st%dun(j)))
            d%tension = max(d%tension, -st%fn(j))
            d%fabs = max(d%fabs, abs(st%fn(j)))
            d%lamabs = max(d%lamabs, abs(st%lam_n(j)))
            d%step = max(d%step, abs(st%fn(j) - st%lam_n(j)))
            if (ifc%friction == FRICTION_NONE) cycle
            d%step = max(d%step, abs(st%ft(j) - st%lam_t(j)))
            if (md%tstate == TS_STICK) then
               d%viol = max(d%viol, abs(st%dut(j)))
               ! a sticking pair within Tresca's bound mu lam_n of its multiplier but
               ! beyond Coulomb's mu F_n of its force (the normal force fell in the
               ! increment by less than the penetration tolerance shows): outside
               ! the cone, not converged; the update lam_n <- F_n lowers its bound
               d%outside = max(d%outside, abs(st%ft(j)) - md%mu*max(st%fn(j), 0.0_dp))
            else if (md%tstate == TS_SLIP) then
               d%coulomb = max(d%coulomb, abs(abs(st%ft(j)) - md%mu*st%fn(j)))
            end if
         end associate
      end do
   end subroutine ideal_defects

   !> Commit ideal pair (state s) at the end of the increment with its forces
   !! fn, ft and slip increment dut.  No elastic layer: all tangential motion
   !! of a slipping pair is irreversible; a sticking one moved by at most
   !! tol_pen.  (A tension left is within the round-off of the run's forces.)
   pure subroutine ideal_commit(ifc, md, fn, ft, dut, s)
      type(interface_t), intent(in) :: ifc
      type(pair_mode_t), intent(in) :: md
      real(dp), intent(in) :: fn, ft, dut
      type(pair_state_t), intent(inout) :: s
      s%closed = md%closed
      s%fn = merge(max(fn, 0.0_dp), 0.0_dp, md%closed)
      s%ft = merge(ft, 0.0_dp, md%closed)
      s%tstate = merge(md%tstate, TS_STICK, md%closed)
      if (md%closed .and. md%tstate == TS_SLIP .and. ifc%friction /= FRICTION_NONE) then
         s%utp = s%utp + dut
         s%utp_gross = s%utp_gross + dut
         s%ve = s%ve + abs(dut)
      end if
   end subroutine ideal_commit
end module contact_ideal_pair
