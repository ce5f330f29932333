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
   implicit none
   private

   public :: pair_state_t, pair_mode_t, contact_state_t
   public :: contact_init, begin_increment, pair_matrix, evaluate_pairs, commit_increment, &
             pair_force_vector, law_drift, check_invariants, augment_multipliers, early_update, &
             pair_dofs, &
             start_force_normal, frozen_pairs, tangential_drift, drop_regularisation, &
             regularise_slip, &
             anchor_regularisation, release_anchors, settle_frozen, open_held_tension, &
             hold_at_rest
   public :: NS_OPEN, NS_LOADING, NS_UNLOADING, TS_STICK, TS_PLASTIC, TS_SLIP
   public :: MAX_SWITCH

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
