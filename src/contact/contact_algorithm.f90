!> The contact algorithm's public face: state determination of the contact
!! springs, the paper's incremental algorithm (section 4; SPEC §4) with the
!! options of SPEC §4.5, and ideal contact (augmented Lagrangian) on the same
!! pairs.  The work is done in four rooms (docs/architecture.md):
!!
!! * contact_pair_types -- the records: a pair's committed state, its mode
!!   within an increment, the state of all pairs (contact_state_t);
!! * contact_state -- initial states, begin and commit of an increment, the
!!   regularising springs, the audits (invariants, drift, frozen pairs);
!! * contact_rough_pair -- one rough pair: its begin, its evaluation after a
!!   solve (the pure function evaluate_rough_pair), its commit;
!! * contact_ideal_pair -- the ideal pairs: evaluation, Uzawa update, commit.
!!
!! This module holds the loop of one evaluation after a solve
!! (evaluate_pairs: the pairs' kinematics, then each rough pair, then each
!! ideal pair, over the lists st%rough and st%ideal) and the pair's matrix and
!! force vector, and re-exports the names its callers use.
module contact_algorithm
   use kinds, only: dp
   use contact_types, only: contact_def_t, contact_pair_t, interface_t, MAX_PAIR_NODES, &
                            FRICTION_NONE
   use contact_element, only: pair_stiffness, pair_kinematics, pair_forces
   use contact_pair_types, only: pair_state_t, pair_mode_t, contact_state_t, MAX_SWITCH, &
                                 NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   use contact_state, only: contact_init, begin_increment, commit_increment, start_force_normal, &
                            drop_regularisation, regularise_slip, check_invariants, frozen_pairs, &
                            law_drift, &
                            tangential_drift
   use contact_rough_pair, only: rough_outcome_t, evaluate_rough_pair, touching_band
   use contact_ideal_pair, only: evaluate_ideal, augment_multipliers, early_update
   use contact_laws, only: normal_pressure, tangential_stiffness
   implicit none
   private

   public :: pair_state_t, pair_mode_t, contact_state_t
   public :: contact_init, begin_increment, pair_matrix, evaluate_pairs, commit_increment, &
             pair_force_vector, law_drift, check_invariants, augment_multipliers, early_update, &
             pair_dofs, &
             start_force_normal, frozen_pairs, tangential_drift, drop_regularisation, &
             regularise_slip, &
             anchor_regularisation, release_anchors, settle_frozen, open_held_tension, &
             hold_at_rest, start_rest, rest_active_set, end_rest
   public :: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   public :: MAX_SWITCH

   !> The tangential spring of a rest pair, a fraction of its K_T^e: it carries no
   !! force (F_T = mu F_n = 0 at zero force), so it only holds the bodies'
   !! tangential rigid-body modes; at K_T^e itself the bodies' tangential
   !! relaxation would be solved with a stiffness the law does not have, and each
   !! solution would leave 0.12-0.15 of the force (the gasket stack).
   real(dp), parameter :: REST_KT = 1.0e-6_dp

contains

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
   !! that pair j changed its mode (the increment must be repeated).  The
   !! kinematics of every pair first, then each rough pair by the pure function
   !! evaluate_rough_pair, then each ideal pair (the pairs are independent).
   pure subroutine evaluate_pairs(cdef, st, du, changed, first)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: du(:, :)          !! (2, npoin) displacement increments
      logical, intent(out) :: changed(:)
      logical, intent(in) :: first              !! first increment (secant iteration option)
      integer :: j, k
      real(dp) :: dun, dut, fpred(size(st%s))
      type(rough_outcome_t) :: r

      changed = .false.
      do j = 1, size(st%s)
         associate (pr => cdef%pairs(j))
            call pair_kinematics(pr%t, pr%n, pr%nn, pr%w, pair_dofs(du, pr), dun, dut)
            ! the normal force the last solution predicted for this pair (its linearisation)
            fpred(j) = st%fn(j) + st%md(j)%kn*(dun - st%dun(j))
            st%dun(j) = dun
            st%dut(j) = dut
         end associate
      end do
      do k = 1, size(st%rough)
         j = st%rough(k)
         if (st%md(j)%rest) then
            ! (placed at rest: the rest spring, no mode check; rest_active_set's)
            call rest_forces(st, j)
            cycle
         end if
         r = evaluate_rough_pair(cdef%ifaces(cdef%pairs(j)%iface), cdef%pairs(j), st%kloc(j), &
                                 cdef%opts, st%s(j), &
                                 st%md(j), st%dun(j), st%dut(j), st%fn(j), fpred(j), &
                                 cdef%opts%p_min_ratio*st%p_start, first, st%regularise, &
                                 st%regularise_slip)
         st%md(j) = r%md
         st%fn(j) = r%fn
         st%ft(j) = r%ft
         if (st%md(j)%anchored) call anchored_forces(cdef%ifaces(cdef%pairs(j)%iface), &
                                                     st%s(j)%un + st%dun(j), &
                                                     st%dut(j), st%md(j), st%fn(j), st%ft(j))
         changed(j) = r%changed
         st%chatter = st%chatter .or. r%chatter
      end do
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         call evaluate_ideal(cdef, st, j, changed(j))
      end do
   end subroutine evaluate_pairs

   !> At a converged solution, the rough pairs frozen by the guard against
   !! chatter (MAX_SWITCH mode changes) evaluated once more as if free to
   !! change their modes, from the modes and forces they have: a pair that
   !! keeps its mode is `settled`, its frozen mode the one its displacements
   !! give (forces on the law, state consistent), and it is no doubt of the
   !! increment (frozen_pairs); one that would change it stays frozen.  Nothing
   !! of the pairs' modes or forces changes here.
   pure subroutine settle_frozen(cdef, st, first)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: first              !! first increment (secant iteration option)
      type(pair_mode_t) :: md
      type(rough_outcome_t) :: r
      integer :: k, j
      do k = 1, size(st%rough)
         j = st%rough(k)
         if (st%md(j)%nswitch < MAX_SWITCH) cycle
         md = st%md(j)
         md%nswitch = 0
         r = evaluate_rough_pair(cdef%ifaces(cdef%pairs(j)%iface), cdef%pairs(j), st%kloc(j), &
                                 cdef%opts, st%s(j), md, st%dun(j), st%dut(j), st%fn(j), st%fn(j), &
                                 cdef%opts%p_min_ratio*st%p_start, first, st%regularise, &
                                 st%regularise_slip)
         ! (a pair on its secant changes its tangential state without a mode change)
         st%md(j)%settled = .not. r%changed .and. (r%md%closed .eqv. md%closed) .and. &
                            (r%md%on_unloading .eqv. md%on_unloading) .and. &
                            r%md%tstate == md%tstate .and. r%md%tsign == md%tsign
         if (.not. st%md(j)%settled) call settle_same_forces(cdef, st, j, r)
      end do
   end subroutine settle_frozen

   !> A frozen rough pair whose free evaluation `r` (settle_frozen) gives another
   !! mode but the same forces, to round-off of the pair's force scale (1e-12, the
   !! scale at which tangential_return calls a pair unloaded): the mode it was
   !! frozen in and the one its displacements give differ only where the law does
   !! not tell them apart -- a pair frozen closed found below its zero-force point
   !! at zero force (open: zero force; generated scene 171, the zero-load end of a
   !! tangential history), or frozen slipping in one direction at zero normal force
   !! (slip in no particular direction, F_T = 0; scene 178).  The solution balances
   !! the law's forces, so it is on the law: the pair takes the mode its
   !! displacements give (for the commit) and is settled, no doubt of the
   !! increment.  Where the forces differ (a frozen mode that carries a force the
   !! law does not give, or the reverse) it stays frozen: the doubt stands.
   pure subroutine settle_same_forces(cdef, st, j, r)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      integer, intent(in) :: j
      type(rough_outcome_t), intent(in) :: r
      real(dp) :: fref
      integer :: nsw
      fref = max(abs(st%s(j)%fn), cdef%pairs(j)%area*max(st%md(j)%pa, r%md%pa), abs(st%fn(j)), &
                 abs(r%fn), tiny(1.0_dp))
      if (abs(r%fn - st%fn(j)) > 1.0e-12_dp*fref .or. abs(r%ft - st%ft(j)) > 1.0e-12_dp*fref) return
      if (r%md%on_unloading .neqv. st%md(j)%on_unloading) return
      nsw = st%md(j)%nswitch
      st%md(j) = r%md
      st%md(j)%nswitch = nsw
      st%md(j)%settled = .true.
      st%fn(j) = r%fn
      st%ft(j) = r%ft
   end subroutine settle_same_forces

   !> RETURN, the second pass of an increment whose system turned singular
   !! (regularise_slip), once the out-of-balance force is within its limit and
   !! only the correction is not: the springs that hold the bodies' rigid-body
   !! modes at zero load (K_T^e of a pair in slip, carrying no force, and the
   !! touching spring of a pair above its band, carrying the law's force) become
   !! elastic elements from the present closure and slip of every closed rough
   !! pair (anchored_forces, from the next evaluation on).  Without a force of
   !! their own they move the bodies in that mode by the left-over force over
   !! their stiffness after every solution, a correction that never shrinks (the
   !! mode has no other stiffness); with it the next solution balances that
   !! force.  release_anchors takes their forces off again once converged.
   pure subroutine anchor_regularisation(st)
      type(contact_state_t), intent(inout) :: st
      integer :: k, j
      do k = 1, size(st%rough)
         j = st%rough(k)
         if (.not. st%md(j)%closed) cycle
         st%md(j)%anchored = .true.
         st%md(j)%un_anc = st%s(j)%un + st%dun(j)
         st%md(j)%ut_anc = st%dut(j)
      end do
   end subroutine anchor_regularisation

   !> The law's forces again (the anchored springs' taken off) for the residual
   !! check of a converged pass and the commit: what the springs carried is
   !! left as out-of-balance force, which must be within the limit.
   pure subroutine release_anchors(st)
      type(contact_state_t), intent(inout) :: st
      integer :: j
      do j = 1, size(st%md)
         if (.not. st%md(j)%anchored) cycle
         st%fn(j) = st%fn(j) - st%md(j)%fn_anc
         st%ft(j) = st%ft(j) - st%md(j)%ft_anc
         st%md(j)%fn_anc = 0.0_dp
         st%md(j)%ft_anc = 0.0_dp
         st%md(j)%anchored = .false.
      end do
   end subroutine release_anchors

   !> RETURN: a rough pair held at the zero-force point of its unloading
   !! branch (below it, on the secant K (u - u_thr): evaluate_rough_pair) that
   !! carries, in a converged iterate, a tension above `flim` (the limit of the
   !! out-of-balance force) is off its law, which gives zero force below u_thr:
   !! the commit would clamp that tension to zero and leave the bodies out of
   !! equilibrium by it (generated scene 74: two pairs at -1e-3 N against a limit
   !! of 4e-6 N, the equilibrium audit 4.9e-7 of the load against 1.4e-8).  Such a
   !! pair opens (a mode change, counted against MAX_SWITCH) and the increment
   !! goes on.  A tension within flim is round-off of the solution; it stays.
   pure subroutine open_held_tension(cdef, st, flim, changed)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: flim              !! the out-of-balance force's limit [force]
      logical, intent(out) :: changed(:)        !! (npair) the pairs opened
      integer :: k, j
      changed = .false.
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (md => st%md(j))
            if (.not. (md%closed .and. md%held) .or. md%touching) cycle
            if (.not. (st%fn(j) < -flim) .or. md%nswitch >= MAX_SWITCH) cycle
            if (cdef%pairs(j)%area <= 0.0_dp) cycle
            md%closed = .false.
            md%newly_closed = .false.
            md%kn = 0.0_dp
            md%kt = 0.0_dp
            md%tstate = TS_STICK
            md%tsign = 0
            md%nswitch = md%nswitch + 1
            st%fn(j) = 0.0_dp
            st%ft(j) = 0.0_dp
            changed(j) = .true.
         end associate
      end do
   end subroutine open_held_tension

   !> RETURN, an increment to zero load: the rough pairs that the last solution
   !! opened, when it left no pair closed at all and the out-of-balance force
   !! within its limit (the caller's test), stay at the zero-force point of their
   !! unloading branch, held there (as evaluate_rough_pair holds a pair found just
   !! below it: the secant from A to the point, K (u - u_thr), which the next
   !! solution brings back to the point), in slip with a force-free K_T^e.  At zero
   !! load every pair's force is zero at equilibrium, so a body held only by the
   !! contact is at rest wherever no pair is pressed: its position is not unique,
   !! and with every pair open the system is singular in the body's rigid-body
   !! modes (generated scenes 49, 66, 169: both attempts stopped singular after a
   !! solution that had balanced every force).  Of those positions this is the one
   !! where the body touches its last pairs, at zero force, where the unloading
   !! has brought it: the rest position the law gives a body set down on its
   !! residual closures.  `changed` flags the pairs held.
   pure subroutine hold_at_rest(cdef, st, was_closed, changed)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: was_closed(:)      !! (npair) closed before the last evaluation
      logical, intent(inout) :: changed(:)      !! (npair)
      integer :: k, j
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (md => st%md(j), pr => cdef%pairs(j))
            if (md%closed .or. .not. (was_closed(j) .and. md%on_unloading)) cycle
            if (pr%area <= 0.0_dp .or. .not. (md%ua > md%uthr)) cycle
            md%closed = .true.
            md%held = .true.
            md%kn = pr%area*md%pa/(md%ua - md%uthr)
            st%fn(j) = min(md%kn*(st%s(j)%un + st%dun(j) - md%uthr), 0.0_dp)
            st%ft(j) = 0.0_dp
            md%tstate = TS_SLIP
            md%tsign = 0
            md%kt = 0.0_dp
            if (cdef%ifaces(pr%iface)%friction /= FRICTION_NONE) md%kt = md%kte
            changed(j) = .true.
         end associate
      end do
   end subroutine hold_at_rest

   !> RETURN, an increment to zero load (the driver's rest_control): every rough
   !! pair on its unloading branch (u_A > u_thr) leaves its law for a linear
   !! spring to its zero-force point, the rest spring F_n = K (u - u_thr) with
   !! K = A p_A/(u_A - u_thr), the secant of the branch from A to the point; the
   !! pairs closed now carry it, the open ones stay open (rest_active_set closes
   !! those the bodies press beyond the point).  At zero load every force of the
   !! answer is zero: each closed pair at its zero-force point, the others below
   !! it, the bodies stress-free -- and a body held only by the contact rests
   !! anywhere no pair is pressed (a half-line of positions: the problem is
   !! singular at its answer).  The law's own tangent vanishes at the point (m2 <
   !! 1: F ~ (u - u_thr)^(1/m2)), so Newton on it approaches the point by a
   !! constant factor a solution (0.87 for m2 = 0.5 in the gasket stack) and
   !! never places the body; the rest spring is linear, so one solution places
   !! the bodies where the springs balance, and the active set (rest_active_set)
   !! ends at the springs that carry no force: the body touching its last pairs
   !! at their zero-force points, where the law's force is zero too.  In slip
   !! (F_T = mu F_n = 0) with a force-free K_T^e of the pair's pressure at A (the
   !! bodies' tangential modes at zero load).  `changed` flags the pairs set.
   pure subroutine start_rest(cdef, st, changed)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(out) :: changed(:)        !! (npair)
      integer :: k, j
      changed = .false.
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (md => st%md(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (pr%area <= 0.0_dp .or. .not. md%on_unloading .or. .not. (md%ua > md%uthr)) cycle
            if (md%anchored) cycle
            md%rest = .true.
            md%held = .false.
            md%touching = .false.
            md%newly_closed = .false.
            md%nswitch = 0
            md%settled = .false.
            md%tstable = .false.
            md%tstate = TS_SLIP
            md%tsign = 0
            md%xb = 0.0_dp
            md%kte = 0.0_dp
            if (ifc%friction /= FRICTION_NONE) md%kte = pr%area*tangential_stiffness(md%pa, ifc%s, &
                                                                                    ifc%r_t(st%kloc(j)))
            call rest_springs(st, j, pr%area)
            changed(j) = .true.
         end associate
      end do
   end subroutine start_rest

   !> The springs of rest pair j for its state (closed: K (u - u_thr) and K_T^e, open: none).
   pure subroutine rest_springs(st, j, area)
      type(contact_state_t), intent(inout) :: st
      integer, intent(in) :: j
      real(dp), intent(in) :: area
      associate (md => st%md(j))
         md%kn = 0.0_dp
         md%kt = 0.0_dp
         if (md%closed) then
            md%kn = area*md%pa/(md%ua - md%uthr)
            md%kt = REST_KT*md%kte
         end if
      end associate
      call rest_forces(st, j)
   end subroutine rest_springs

   !> The forces of rest pair j: its rest spring's, F_T = 0.
   pure subroutine rest_forces(st, j)
      type(contact_state_t), intent(inout) :: st
      integer, intent(in) :: j
      st%fn(j) = 0.0_dp
      st%ft(j) = 0.0_dp
      if (st%md(j)%closed) st%fn(j) = st%md(j)%kn*(st%s(j)%un + st%dun(j) - st%md(j)%uthr)
   end subroutine rest_forces

   !> The active set of the rest springs at a balanced solution: a closed rest
   !! pair pulled by more than `flim` (the out-of-balance force's limit) opens,
   !! an open one pressed beyond its zero-force point by more than flim over its
   !! spring's stiffness closes.  `changed` flags them; the caller solves again.
   pure subroutine rest_active_set(cdef, st, flim, changed)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: flim
      logical, intent(out) :: changed(:)
      integer :: k, j
      real(dp) :: kr
      changed = .false.
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (md => st%md(j))
            if (.not. md%rest) cycle
            kr = cdef%pairs(j)%area*md%pa/(md%ua - md%uthr)
            if (md%closed .and. st%fn(j) < -flim) then
               md%closed = .false.
            else if (.not. md%closed .and. kr*(st%s(j)%un + st%dun(j) - md%uthr) > flim) then
               md%closed = .true.
            else
               cycle
            end if
            call rest_springs(st, j, cdef%pairs(j)%area)
            changed(j) = .true.
         end associate
      end do
   end subroutine rest_active_set

   !> The rest found (no rest pair changes its state): the law back at every
   !! rest pair.  `ok` when every closed rest pair carries at most `flim`
   !! (a force of the answer at zero load is zero): it then is touching at its
   !! zero-force point with the law's force there (round-off: the commit's
   !! touching pair), the open ones open.  A pair pressed beyond flim means the
   !! bodies carry a force at zero load (a fit, a prescribed gap): not ok, the
   !! pairs keep their states and the law's forces, and the iteration goes on
   !! with the law.  Either way no pair is a rest pair any more.
   pure subroutine end_rest(cdef, st, flim, ok)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: flim
      logical, intent(out) :: ok
      integer :: k, j
      ok = .true.
      do k = 1, size(st%rough)
         j = st%rough(k)
         if (st%md(j)%rest .and. st%md(j)%closed) ok = ok .and. st%fn(j) <= flim
      end do
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (md => st%md(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. md%rest) cycle
            md%rest = .false.
            if (.not. md%closed) cycle
            md%touching = ok
            md%held = ok
            st%fn(j) = cdef%pairs(j)%area*normal_pressure(st%s(j)%un + st%dun(j), ifc%cn, ifc%m, &
                                                          ifc%cn2, ifc%m2, .true., md%ua, md%pa)
            st%ft(j) = 0.0_dp
         end associate
      end do
   end subroutine end_rest

   !> The forces of an anchored pair's regularising springs (anchor_regularisation),
   !! added to the law's fn and ft: the touching spring of a pair above the spring's
   !! band (where the pair carries the law's force with the spring's stiffness) and
   !! the K_T^e of a pair in slip, each from the anchor, so that the pair carries
   !! what the solve predicts for it.
   pure subroutine anchored_forces(ifc, u, dut, md, fn, ft)
      type(interface_t), intent(in) :: ifc
      real(dp), intent(in) :: u, dut           !! closure and slip increment now
      type(pair_mode_t), intent(inout) :: md
      real(dp), intent(inout) :: fn, ft
      md%fn_anc = 0.0_dp
      md%ft_anc = 0.0_dp
      if (.not. md%closed) return
      if (md%touching .and. u - md%uthr > touching_band(ifc, md, .false.)) then
         md%fn_anc = md%kn*(u - md%un_anc)
      end if
      if (md%tstate == TS_SLIP .and. .not. md%tstable .and. md%kt > 0.0_dp) then
         md%ft_anc = md%kt*(dut - md%ut_anc)
      end if
      fn = fn + md%fn_anc
      ft = ft + md%ft_anc
   end subroutine anchored_forces
end module contact_algorithm
