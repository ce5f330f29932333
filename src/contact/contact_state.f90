!> The contact state: the states of all pairs through a run -- initial states
!! (contact_init), the start of an increment (begin_increment: the modes and
!! stiffnesses of the first solve), its end (commit_increment: the committed
!! state), the switches of the rough pairs' regularising springs, and the
!! audits of the committed states (SPEC §7 invariants, law drift, tangential
!! drift, frozen pairs).  The per-pair work is the law's room: contact_rough_pair
!! (the paper's incremental algorithm, section 4; SPEC §4) and contact_ideal_pair
!! (augmented Lagrangian); the loops here run over the lists st%rough and
!! st%ideal.  The evaluation after a solve is contact_algorithm's.
module contact_state
   use kinds, only: dp
   use contact_types, only: contact_def_t, LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, UPDATE_RETURN
   use contact_laws, only: normal_pressure, friction_coefficient, bilinear_return
   use roundoff, only: roundoff_floor
   use contact_pair_types, only: pair_state_t, pair_mode_t, contact_state_t, MAX_SWITCH
   use contact_rough_pair, only: rough_begin, rough_commit, set_kt
   use contact_ideal_pair, only: ideal_begin, ideal_commit
   implicit none
   private

   public :: contact_init, begin_increment, commit_increment, start_force_normal, is_ideal, &
             drop_regularisation, regularise_slip, check_invariants, frozen_pairs, law_drift, &
             tangential_drift

contains

   !> Initial states: closure -g0; closed if the gap is within tolerance (or
   !! among the n_start smallest gaps).  Penalty stiffnesses and tolerance of
   !! the ideal law.  The lists of the rough and the ideal pairs.
   subroutine contact_init(cdef, gap_tol, st)
      type(contact_def_t), intent(in) :: cdef
      real(dp), intent(in) :: gap_tol
      type(contact_state_t), intent(out) :: st
      integer :: np, j, k, nclose
      integer :: order(size(cdef%pairs)), nof(size(cdef%ifaces))
      real(dp) :: g(size(cdef%pairs)), hmin
      np = size(cdef%pairs)
      ! the pairs by law, and each pair's position among the pairs of its interface
      st%rough = pack([(j, j=1, np)], [(.not. is_ideal(cdef, j), j=1, np)])
      st%ideal = pack([(j, j=1, np)], [(is_ideal(cdef, j), j=1, np)])
      allocate (st%kloc(np))
      nof = 0
      do j = 1, np
         nof(cdef%pairs(j)%iface) = nof(cdef%pairs(j)%iface) + 1
         st%kloc(j) = nof(cdef%pairs(j)%iface)
      end do
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
      ! tangentially a softer penalty (a layer of thickness h/sqrt(FACTOR), not
      ! h/FACTOR): the trial force of a sticking pair, lam_T + eps_T du_T, must not
      ! swing across the whole friction cone for a tiny du_T, or the stick/slip
      ! modes chatter; and not as soft as a layer of thickness h (eps_n/FACTOR, until
      ! this version), whose multiplier iteration converged at about 0.8 an update
      ! (a frictional rigid ball unloaded to zero took 240 solutions in 8
      ! increments, 81 now; docs/contact.md)
      st%eps_t = st%eps_n/sqrt(cdef%opts%aug_factor)
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
      else if (.not. any(st%s%closed)) then
         ! no pair closed by its gap: MATCHING SEGMENT averages the gap over a node's zone, so a
         ! curved surface touching B at a node (a roller on a block) has g0 > 0 at every pair
         ! and a body held by the contact alone would be unsupported; the nodes touching B
         ! themselves (g_point <= gap_tol) start closed, as START NSTART would close them
         do j = 1, np
            st%s(j)%closed = cdef%pairs(j)%g_point <= gap_tol .and. active(cdef, j)
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

   !> Modes and stiffnesses for the next increment from the committed states.
   !! In the first increment closed pairs get the secants of eqs. (4.5), (4.6)
   !! at the start pressure p_m; later the tangents of eqs. (4.10), (4.11).
   !! Ideal pairs keep their committed modes, get the penalty stiffnesses and
   !! start the Uzawa iteration from their committed forces.
   pure subroutine begin_increment(cdef, st, first)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: first
      integer :: j, k
      real(dp) :: pfloor
      logical :: returning
      pfloor = cdef%opts%p_min_ratio*st%p_start
      returning = cdef%opts%update == UPDATE_RETURN
      st%augmentations = 0
      st%violation = 0.0_dp
      st%coulomb = .false.
      st%regularise = .true.
      st%regularise_slip = .false.
      do j = 1, size(st%s)
         st%md(j) = pair_mode_t()
         ! the forces and increments of the last evaluation are those of the start
         st%fn(j) = st%s(j)%fn
         st%ft(j) = st%s(j)%ft
         st%dun(j) = 0.0_dp
         st%dut(j) = 0.0_dp
      end do
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         call ideal_begin(cdef%ifaces(cdef%pairs(j)%iface), st%s(j), st%eps_n(j), st%eps_t(j), &
                          st%md(j), &
                          st%lam_n(j), st%lam_t(j))
      end do
      do k = 1, size(st%rough)
         j = st%rough(k)
         call rough_begin(cdef%ifaces(cdef%pairs(j)%iface), cdef%pairs(j), st%kloc(j), st%s(j), &
                          st%md(j), &
                          first, returning, st%p_start, pfloor, st%p_incr)
      end do
   end subroutine begin_increment

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
      integer :: j, k
      real(dp) :: kt0
      if (.not. st%regularise .or. cdef%opts%update /= UPDATE_RETURN) return
      st%regularise = .false.
      do k = 1, size(st%rough)
         j = st%rough(k)
         associate (ifc => cdef%ifaces(cdef%pairs(j)%iface))
            ! (a pair whose tangential states cycle keeps its secant, within [0.05, 1] K_T^e)
            ! (and a rest pair its force-free K_T^e: start_rest)
            if (st%md(j)%tstable .or. st%md(j)%rest) cycle
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

   !> Commit the increment: totals, branch, irreversible slip, effective slip.
   pure subroutine commit_increment(cdef, st)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(inout) :: st
      integer :: j, k
      real(dp) :: ft_old
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j))
            s%un = s%un + st%dun(j)
            s%ut = s%ut + st%dut(j)
            s%mu = md%mu
            s%kn = md%kn
            s%kt = md%kt
         end associate
      end do
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         call ideal_commit(cdef%ifaces(cdef%pairs(j)%iface), st%md(j), st%fn(j), st%ft(j), &
                           st%dut(j), st%s(j))
         st%fref = max(st%fref, st%s(j)%fn)
      end do
      do k = 1, size(st%rough)
         j = st%rough(k)
         ft_old = st%s(j)%ft
         call rough_commit(cdef%ifaces(cdef%pairs(j)%iface), cdef%pairs(j), st%md(j), st%fn(j), &
                           st%ft(j), ft_old, &
                           st%dut(j), st%s(j))
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
      real(dp), intent(in), optional :: fscale    !! the run's force scale (absent:
                                                  !! the largest committed |F_n|)
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
            if (s%closed .and. s%fn < -tol) then
               call bad('pair '//trim(b)//' is closed with a tensile normal force')
            end if
            if (.not. s%closed .and. (abs(s%fn) > 0.0_dp .or. abs(s%ft) > 0.0_dp)) then
               call bad('pair '//trim(b)//' is open but carries a force')
            end if
            if (abs(s%ft) > s%mu*max(s%fn, 0.0_dp) + tol) then
               call bad('pair '//trim(b)//' has |F_T| > mu F_n')
            end if
            if (s%ve < ve_old(j) - 1.0e-14_dp*max(1.0_dp, ve_old(j))) then
               call bad('pair '//trim(b)//': the effective slip decreased')
            end if
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
   !! changed their modes MAX_SWITCH times and kept the last one (chatter),
   !! and at the end of the increment, free to change it, would have left it
   !! (a pair whose frozen mode is the one its final displacements give is on
   !! its law like any other: pair_mode_t%settled, contact_algorithm's
   !! settle_frozen).  Ideal pairs are never frozen (their active set iterates
   !! to the end).
   pure function frozen_pairs(cdef, st) result(list)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, allocatable :: list(:)      !! pair numbers, ascending
      integer :: j
      list = pack([(j, j=1, size(st%md))], [(st%md(j)%nswitch >= MAX_SWITCH .and. &
                                             .not. st%md(j)%settled .and. &
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
            f = pr%area*normal_pressure(s%un, ifc%cn, ifc%m, ifc%cn2, ifc%m2, s%on_unloading, &
                                        s%ua, s%pa)
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
      real(dp), allocatable, intent(inout) :: tlaw(:, :)  !! (3, npair) the law's F_T,
                                                          !! back force, and F_n
      real(dp), intent(out) :: drift                 !! relative to the largest
                                                     !! mu F_n of the closed pairs
      integer, intent(out) :: worst                  !! the pair farthest off (0: none)
      integer :: j, itrial
      real(dp) :: fmax, f0, x0, ft, xb, d, dmax, fpeak
      !> the forces' achievable accuracy: Newton's TOLR (1e-10 of the forces), raised by the
      !! round-off of the forces that cancel up to about 1e-8 of them (step_audit's floors)
      real(dp), parameter :: FORCE_ACCURACY = 1.0e-8_dp
      if (.not. allocated(tlaw)) then
         allocate (tlaw(3, size(st%s)))
         tlaw = 0.0_dp
      end if
      drift = 0.0_dp
      worst = 0
      fmax = 0.0_dp
      fpeak = 0.0_dp
      dmax = 0.0_dp
      do j = 1, size(st%s)
         associate (s => st%s(j), md => st%md(j), pr => cdef%pairs(j), &
                    ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. s%closed .or. ifc%law /= LAW_ROUGH .or. ifc%friction == FRICTION_NONE) then
               tlaw(:, j) = 0.0_dp
               cycle
            end if
            f0 = merge(0.0_dp, tlaw(1, j), md%newly_closed)
            x0 = merge(0.0_dp, tlaw(2, j), md%newly_closed)
            call bilinear_return(f0, st%dut(j), md%kte, ifc%kappa, md%mu*max(s%fn, 0.0_dp), x0, &
                                 ifc%hardening, &
                                 ft, xb, itrial)
            d = abs(s%ft - ft)
            if (s%fn <= 1.0e-12_dp*max(tlaw(3, j), pr%area*md%pa, tiny(1.0_dp))) then
               ft = 0.0_dp
               xb = 0.0_dp
               ! at zero normal force to round-off the law holds any |F_T| <= mu F_n (a
               ! touching pair's committed force is clamped there, commit_increment)
               d = max(abs(s%ft) - md%mu*max(s%fn, 0.0_dp), 0.0_dp)
            end if
            fpeak = max(fpeak, md%mu*max(tlaw(3, j), pr%area*md%pa, s%fn))
            tlaw(:, j) = [ft, xb, s%fn]
            fmax = max(fmax, md%mu*s%fn)
            if (d > dmax) then
               dmax = d
               worst = j
            end if
         end associate
      end do
      ! relative to the largest mu F_n now, but not below the accuracy the forces can have,
      ! FORCE_ACCURACY of the largest friction force the closed pairs carried (the last
      ! increment's or their reversal point's): at zero load, pairs at rest touching with
      ! F_n ~ 1e-13 N, whose law's F_T = mu F_n is round-off, are no drift (a generated scene,
      ! 88, reported "100 % of mu F_n off the tangential law" for 7e-14 N)
      fmax = max(fmax, FORCE_ACCURACY*fpeak)
      if (fmax > 0.0_dp) then
         drift = dmax/fmax
      else
         worst = 0
      end if
   end subroutine tangential_drift
end module contact_state
