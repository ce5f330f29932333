!> Energy dissipated by the contact laws: per pair, per interface, per load
!! cycle (docs/contact.md, "Energy dissipated by the interface").
!!
!! Computed once per accepted step from the committed pair states at the
!! start and at the end of the step, along the law between them where the law
!! is known (not by chords):
!!
!! * tangential (rough law): the bilinear law read as two Jenkins elements
!!   (spring and Coulomb slider) in parallel, which is what `bilinear_return`
!!   integrates (Masing's rule).  The dissipation is the work of the sliders:
!!   (1 - kappa) r_y |du| on the hardening branch (the first slider slips at
!!   its force (1 - kappa) r_y, r_y = 0.625 mu F_n), mu F_n |du| in gross slip
!!   (both slip), nothing in stick; the path of the step (elastic, branch,
!!   slip) is that of `bilinear_return` from the committed force and back force
!!   with the step's K_T^e and mu F_n.  Over a closed cycle at constant
!!   K_T^e and mu F_n this is the area of the loop, the integral of F_T along
!!   u_T^p (= the integral of F_T du_T);
!! * tangential (ideal law, Coulomb): F_T du_T of a slipping pair (all its
!!   tangential motion is irreversible);
!! * normal (rough law): W - R, W the work F_n du_n done on the pair along the
!!   law (virgin curve u = cn p^m and unloading branches
!!   u = u_A - cn2' (p_A^m2 - p^m2), integrated in closed form), R the energy
!!   the pair would give back unloading along its branch from the current
!!   state to zero force: after a cycle the area between loading and
!!   unloading branches.  The ideal law has no normal hysteresis.
!!
!! Periodic histories: a cycle runs from a reversal of the load history
!! (the load factors' change reverses its direction) to the next point that
!! returns to the same load factors with at least one reversal between
!! (`find_cycles`).  No module below the driver calls it; the driver keeps an
!! `energy_t` and calls, per accepted step, `energy_begin` before the contact
!! states are committed and `energy_commit` after, `energy_fields` when the
!! contact fields are built, and `energy_cycles` at the end.
!!
!! Ref: W. D. Iwan, J. Appl. Mech. 33 (1966) 893-900 (parallel Jenkins
!! elements, Masing's rule); K. L. Johnson, Contact Mechanics (1985) ch. 7.
module contact_energy
   use kinds, only: dp
   use contact_types, only: contact_def_t, interface_t, LAW_ROUGH, LAW_IDEAL, FRICTION_NONE
   use contact_laws, only: unloading_constant, virgin_closure
   use contact_algorithm, only: contact_state_t, pair_state_t, TS_SLIP
   use records, only: contact_fields_t, cycle_table_t
   implicit none
   private
   public :: energy_t, energy_init, energy_begin, energy_commit, energy_fields, energy_cycles
   public :: slider_dissipation, virgin_work, branch_work, normal_work, normal_recoverable, &
         find_cycles

   !> What the run keeps for the energy bookkeeping.
   type :: energy_t
      logical :: active = .false.
      type(pair_state_t), allocatable :: start(:)   !! committed states at the start of the step
      real(dp), allocatable :: work_n(:)            !! (npair) cumulative work of F_n along the law
      real(dp), allocatable :: diss_n(:), diss_t(:) !! (npair) cumulative dissipation
      real(dp), allocatable :: diss_step(:)         !! (niface) dissipated in the last step
      ! history of the steps (point 0: the start of the run)
      integer :: npoint = 0
      integer, allocatable :: step(:)               !! (0:) step number of each point
      real(dp), allocatable :: lambda(:, :)         !! (ncase, 0:) load factors
      real(dp), allocatable :: hist(:, :, :)        !! (3, niface, 0:) cumulative dissipation,
                                                    !! sum F_T, mean u_T
      logical, allocatable :: compliant(:)          !! (niface) a rough interface: tangential
                                                    !! springs, its mean u_T a displacement
   end type energy_t

contains

   !> Start of the run: zero energies, the initial load factors as point 0.
   subroutine energy_init(cdef, st, lambda0, en)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: lambda0(:)            !! load factors at the start of the history
      type(energy_t), intent(out) :: en
      integer :: np, ni
      np = 0
      if (allocated(cdef%pairs)) np = size(cdef%pairs)
      ni = 0
      if (allocated(cdef%ifaces)) ni = size(cdef%ifaces)
      en%active = np > 0 .and. ni > 0 .and. allocated(st%s)
      allocate (en%work_n(np), en%diss_n(np), en%diss_t(np), en%diss_step(ni))
      en%work_n = 0.0_dp
      en%diss_n = 0.0_dp
      en%diss_t = 0.0_dp
      en%diss_step = 0.0_dp
      allocate (en%step(0:15), en%lambda(size(lambda0), 0:15), en%hist(3, ni, 0:15))
      en%npoint = 0
      en%step(0) = 0
      en%lambda(:, 0) = lambda0
      en%hist(:, :, 0) = 0.0_dp
      allocate (en%compliant(ni), source=.true.)
      if (ni > 0) en%compliant = cdef%ifaces(1:ni)%law /= LAW_IDEAL
      if (en%active) en%start = st%s
   end subroutine energy_init

   !> Before the step's states are committed: keep the start states.
   subroutine energy_begin(st, en)
      type(contact_state_t), intent(in) :: st
      type(energy_t), intent(inout) :: en
      if (en%active) en%start = st%s
   end subroutine energy_begin

   !> After the step's states are committed: the energies of the step, and the
   !! step as a point of the history.
   subroutine energy_commit(cdef, st, step, lambda, en)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st    !! committed states (st%md, st%dut: the step's)
      integer, intent(in) :: step                !! number of the accepted step
      real(dp), intent(in) :: lambda(:)          !! its load factors
      type(energy_t), intent(inout) :: en
      integer :: j, ni, k
      real(dp) :: f0, x0, dt, before(size(en%diss_step)), tot(size(en%diss_step))
      if (.not. en%active) return
      ni = size(en%diss_step)
      before = interface_sum(cdef, en%diss_n + en%diss_t, ni)
      do j = 1, size(st%s)
         associate (s0 => en%start(j), s1 => st%s(j), md => st%md(j), pr => cdef%pairs(j), &
                    ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (pr%area <= 0.0_dp) cycle
            if (ifc%law == LAW_ROUGH) then
               en%work_n(j) = en%work_n(j) + normal_work(ifc, pr%area, s0, s1)
               en%diss_n(j) = en%work_n(j) - normal_recoverable(ifc, pr%area, s1)
            end if
            if (.not. s1%closed .or. ifc%friction == FRICTION_NONE) cycle
            dt = 0.0_dp
            if (ifc%law == LAW_IDEAL) then
               if (md%tstate == TS_SLIP) dt = max(s1%ft*st%dut(j), 0.0_dp)
            else if (md%kte > 0.0_dp) then
               f0 = merge(0.0_dp, s0%ft, md%newly_closed .or. .not. s0%closed)
               x0 = merge(0.0_dp, s0%xb, md%newly_closed .or. .not. s0%closed)
               dt = slider_dissipation(f0, st%dut(j), md%kte, ifc%kappa, &
                                       md%mu*max(s1%fn, 0.0_dp), x0, ifc%hardening)
            end if
            en%diss_t(j) = en%diss_t(j) + dt
         end associate
      end do
      tot = interface_sum(cdef, en%diss_n + en%diss_t, ni)
      en%diss_step = tot - before
      ! the step as a point of the history
      k = en%npoint + 1
      if (k > ubound(en%step, 1)) call grow(en)
      en%npoint = k
      en%step(k) = step
      en%lambda(:, k) = lambda
      en%hist(1, :, k) = tot
      call interface_motion(cdef, st, ni, en%hist(2, :, k), en%hist(3, :, k))
   end subroutine energy_commit

   !> The energy part of the contact fields record of the last committed step.
   subroutine energy_fields(cdef, st, en, cf)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      type(energy_t), intent(in) :: en
      type(contact_fields_t), intent(inout) :: cf
      integer :: ni
      if (.not. en%active) return
      ni = size(en%diss_step)
      cf%dissipation_tangential = en%diss_t
      cf%dissipation_normal = en%diss_n
      cf%dissipated_energy = interface_sum(cdef, en%diss_n + en%diss_t, ni)
      cf%dissipated_increment = en%diss_step
      if (allocated(cf%tangential_force_total)) deallocate (cf%tangential_force_total)
      if (allocated(cf%slip_mean)) deallocate (cf%slip_mean)
      allocate (cf%tangential_force_total(ni), cf%slip_mean(ni))
      call interface_motion(cdef, st, ni, cf%tangential_force_total, cf%slip_mean)
   end subroutine energy_fields

   !> The cycles of the history so far (find_cycles) and their figures.
   subroutine energy_cycles(en, tab)
      type(energy_t), intent(in) :: en
      type(cycle_table_t), intent(out) :: tab
      integer, allocatable :: c0(:), c1(:)
      integer :: ic, ni, i
      real(dp) :: u
      if (.not. en%active) return
      call find_cycles(en%lambda(:, 0:en%npoint), c0, c1)
      ni = size(en%diss_step)
      tab%ncycle = size(c0)
      allocate (tab%first(tab%ncycle), tab%last(tab%ncycle))
      allocate (tab%energy(ni, tab%ncycle), tab%force_amplitude(ni, tab%ncycle), &
                tab%slip_amplitude(ni, tab%ncycle), &
                tab%secant_stiffness(ni, tab%ncycle), tab%loss_factor(ni, tab%ncycle), &
                tab%damping_ratio(ni, tab%ncycle))
      do ic = 1, tab%ncycle
         ! c0, c1 are 1-based indices into points 0..npoint
         associate (h => en%hist(:, :, c0(ic) - 1:c1(ic) - 1))
            tab%first(ic) = en%step(c0(ic) - 1)
            tab%last(ic) = en%step(c1(ic) - 1)
            do i = 1, ni
               tab%energy(i, ic) = h(1, i, size(h, 3)) - h(1, i, 1)
               tab%force_amplitude(i, ic) = 0.5_dp*(maxval(h(2, i, :)) - minval(h(2, i, :)))
               tab%slip_amplitude(i, ic) = 0.5_dp*(maxval(h(3, i, :)) - minval(h(3, i, :)))
            end do
         end associate
      end do
      ! The ratios describe the interface as one hysteretic element, the loop of (sum F_T,
      ! mean u_T). They are not defined (0) (a) for an ideal interface: its sticking pairs do
      ! not move, so its mean u_T is the slip of its slipping pairs alone, no displacement of
      ! the joint that the total force works on (a bolt head's: loss factor 17.7, damping ratio
      ! 8.8 before); (b) where the energy of the cycle exceeds 4 F_amp u_amp, the rectangle
      ! that bounds every loop of those amplitudes (so eta <= 4/pi, Coulomb's rigid-plastic
      ! loop): the pairs' slips then do not follow the total force -- they cancel in it, as
      ! the faces of a seal ring that slide outwards and inwards under a normal load cycle
      ! (loss factor 14.6 before).
      allocate (tab%ratios_defined(ni, tab%ncycle), source=.true.)
      do ic = 1, tab%ncycle
         do i = 1, ni
            if (allocated(en%compliant)) tab%ratios_defined(i, ic) = en%compliant(i)
            if (tab%energy(i, ic) > 4.0_dp*tab%force_amplitude(i, ic)* &
                tab%slip_amplitude(i, ic)) tab%ratios_defined(i, ic) = .false.
         end do
      end do
      do ic = 1, tab%ncycle
         do i = 1, ni
            tab%secant_stiffness(i, ic) = 0.0_dp
            tab%loss_factor(i, ic) = 0.0_dp
            if (.not. tab%ratios_defined(i, ic)) cycle
            if (tab%slip_amplitude(i, ic) > 0.0_dp) then
               tab%secant_stiffness(i, ic) = tab%force_amplitude(i, ic)/tab%slip_amplitude(i, ic)
            end if
            u = 0.5_dp*tab%force_amplitude(i, ic)*tab%slip_amplitude(i, ic)
            if (u > 0.0_dp) tab%loss_factor(i, ic) = tab%energy(i, ic)/(2.0_dp*acos(-1.0_dp)*u)
         end do
      end do
      tab%damping_ratio = 0.5_dp*tab%loss_factor
   end subroutine energy_cycles

   !> The cycles of a load history given at points 1..n (columns of lam):
   !! point k (1 < k < n) is a reversal when the load factors change into it
   !! and the next change out of it (points without change skipped: a hold)
   !! points against that one (negative dot product).  A cycle starts at a
   !! reversal and ends at the first later point -- a reversal, or the point
   !! where the history's last change ends -- whose load factors equal the
   !! start's (to 1e-9 of the
   !! largest |factor| of the history) with at least one reversal between;
   !! the next cycle starts where it ended (when that is a reversal), else at
   !! the next reversal.  c0, c1: first and last point of each cycle.
   pure subroutine find_cycles(lam, c0, c1)
      real(dp), intent(in) :: lam(:, :)           !! (ncase, n) load factors of the points
      integer, allocatable, intent(out) :: c0(:), c1(:)
      integer :: n, k, kn, nrev, i, j, jr, a, b, last
      integer :: rev(size(lam, 2))
      logical :: isrev(size(lam, 2))
      real(dp) :: tol
      n = size(lam, 2)
      allocate (c0(0), c1(0))
      isrev = .false.
      if (n < 3) return
      tol = 1.0e-9_dp*max(maxval(abs(lam)), tiny(1.0_dp))
      do k = 2, n - 1
         if (.not. moves(k)) cycle
         do kn = k + 1, n
            if (moves(kn)) exit
         end do
         if (kn > n) exit
         isrev(k) = dot_product(lam(:, k) - lam(:, k - 1), lam(:, kn) - lam(:, kn - 1)) < 0.0_dp
      end do
      last = 1
      do k = 2, n
         if (moves(k)) last = k
      end do
      nrev = 0
      do k = 1, n
         if (isrev(k)) then
            nrev = nrev + 1
            rev(nrev) = k
         end if
      end do
      i = 1
      do while (i <= nrev)
         a = rev(i)
         b = 0
         jr = 0
         do j = a + 1, n
            if (isrev(j)) jr = jr + 1
            if (.not. (isrev(j) .or. j == last)) cycle
            if (jr - merge(1, 0, isrev(j)) < 1) cycle
            if (all(abs(lam(:, j) - lam(:, a)) <= tol)) then
               b = j
               exit
            end if
         end do
         if (b == 0) then
            i = i + 1
            cycle
         end if
         c0 = [c0, a]
         c1 = [c1, b]
         if (.not. isrev(b)) exit
         do while (i <= nrev)
            if (rev(i) >= b) exit
            i = i + 1
         end do
      end do
   contains
      !> The load factors change from point k - 1 to point k.
      pure logical function moves(k)
         integer, intent(in) :: k
         moves = any(abs(lam(:, k) - lam(:, k - 1)) > tol)
      end function moves
   end subroutine find_cycles

   !> Dissipation of the bilinear tangential law over one increment: the work
   !! of the sliders of its two Jenkins elements along the path of
   !! `bilinear_return` (same arguments): none in the elastic band,
   !! (1 - kappa) r_y per unit displacement on the hardening branch (the
   !! first slider, at its force (1 - kappa) r_y), L = mu F_n per unit
   !! displacement in gross slip.  Without the branch (r_y = L) only slip.
   pure real(dp) function slider_dissipation(f0, du, ke, kappa, limit, x0, hardening) result(d)
      real(dp), intent(in) :: f0, du, ke, kappa, limit, x0
      logical, intent(in) :: hardening
      real(dp) :: ry, xcap, x, trial, s, fe, fb, dub, dus
      d = 0.0_dp
      if (ke <= 0.0_dp .or. limit <= 0.0_dp) return
      ry = merge(0.625_dp*limit, limit, hardening)
      xcap = max(limit - ry, 0.0_dp)
      x = min(max(x0, -xcap), xcap)
      trial = f0 + ke*du
      if (abs(trial - x) <= ry) return
      s = sign(1.0_dp, trial - x)
      fe = x + s*ry                        ! the band's edge
      ! displacement beyond the edge (the law's reading: trial - edge over K_T^e)
      dus = abs(trial - fe)/ke
      if (hardening) then
         fb = fe + kappa*(trial - fe)      ! where the branch would end
         if (abs(fb) <= limit .or. kappa <= 0.0_dp) then
            d = (1.0_dp - kappa)*ry*dus
            return
         end if
         dub = abs(s*limit - fe)/(kappa*ke)
         d = (1.0_dp - kappa)*ry*dub + limit*max(dus - dub, 0.0_dp)
      else
         d = limit*dus
      end if
   end function slider_dissipation

   !> Work per unit area along the virgin curve u = cn p^m from 0 to p:
   !! int p du = cn m / (m + 1) p^(m+1).
   elemental real(dp) function virgin_work(p, cn, m) result(w)
      real(dp), intent(in) :: p, cn, m
      w = cn*m/(m + 1.0_dp)*max(p, 0.0_dp)**(m + 1.0_dp)
   end function virgin_work

   !> Work per unit area along an unloading branch u = u_A - c (p_A^m2 - p^m2)
   !! from zero force to p: int p du = c m2 / (m2 + 1) p^(m2+1) (c the branch's
   !! constant, unloading_constant).
   elemental real(dp) function branch_work(p, c, m2) result(w)
      real(dp), intent(in) :: p, c, m2
      w = c*m2/(m2 + 1.0_dp)*max(p, 0.0_dp)**(m2 + 1.0_dp)
   end function branch_work

   !> Work F_n du_n done on a rough pair from state s0 to state s1 along the
   !! normal law: up (or down) its branch to the reversal point, along the
   !! virgin curve, down the new branch; p = F_n / A (0 when open).
   pure real(dp) function normal_work(ifc, area, s0, s1) result(w)
      type(interface_t), intent(in) :: ifc
      real(dp), intent(in) :: area
      type(pair_state_t), intent(in) :: s0, s1
      real(dp) :: p0, p1, c0, c1, pv
      p0 = pressure(s0, area)
      p1 = pressure(s1, area)
      c0 = unloading_constant(s0%ua, s0%pa, ifc%cn2, ifc%m2)
      c1 = unloading_constant(s1%ua, s1%pa, ifc%cn2, ifc%m2)
      if (s0%on_unloading .and. s1%on_unloading .and. abs(s0%ua - s1%ua) <= &
            epsilon(1.0_dp)*abs(s1%ua) .and. &
          abs(s0%pa - s1%pa) <= epsilon(1.0_dp)*abs(s1%pa)) then
         w = area*(branch_work(p1, c1, ifc%m2) - branch_work(p0, c0, ifc%m2))
         return
      end if
      ! from s0 to the virgin curve
      pv = p0
      w = 0.0_dp
      if (s0%on_unloading) then
         w = branch_work(s0%pa, c0, ifc%m2) - branch_work(p0, c0, ifc%m2)
         pv = s0%pa
      end if
      if (s1%on_unloading) then
         w = w + virgin_work(s1%pa, ifc%cn, ifc%m) - virgin_work(pv, ifc%cn, ifc%m) + &
             branch_work(p1, c1, ifc%m2) - branch_work(s1%pa, c1, ifc%m2)
      else
         w = w + virgin_work(p1, ifc%cn, ifc%m) - virgin_work(pv, ifc%cn, ifc%m)
      end if
      w = area*w
   end function normal_work

   !> Energy a rough pair gives back unloading from its state s along its
   !! unloading branch (the branch it is on, or the one a reversal now would
   !! start) to zero force.
   pure real(dp) function normal_recoverable(ifc, area, s) result(r)
      type(interface_t), intent(in) :: ifc
      real(dp), intent(in) :: area
      type(pair_state_t), intent(in) :: s
      real(dp) :: p, c
      p = pressure(s, area)
      if (s%on_unloading) then
         c = unloading_constant(s%ua, s%pa, ifc%cn2, ifc%m2)
      else
         c = unloading_constant(virgin_closure(p, ifc%cn, ifc%m), p, ifc%cn2, ifc%m2)
      end if
      r = area*branch_work(p, c, ifc%m2)
   end function normal_recoverable

   pure real(dp) function pressure(s, area) result(p)
      type(pair_state_t), intent(in) :: s
      real(dp), intent(in) :: area
      p = 0.0_dp
      if (s%closed .and. area > 0.0_dp) p = max(s%fn, 0.0_dp)/area
   end function pressure

   !> Sum of a per-pair quantity over each interface's pairs.
   pure function interface_sum(cdef, v, ni) result(tot)
      type(contact_def_t), intent(in) :: cdef
      real(dp), intent(in) :: v(:)
      integer, intent(in) :: ni
      real(dp) :: tot(ni)
      integer :: j
      tot = 0.0_dp
      do j = 1, size(v)
         tot(cdef%pairs(j)%iface) = tot(cdef%pairs(j)%iface) + v(j)
      end do
   end function interface_sum

   !> Per interface the sum of F_T and the area-weighted mean u_T of the closed pairs (0: none
   !> closed).
   pure subroutine interface_motion(cdef, st, ni, ftot, smean)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: ni
      real(dp), intent(out) :: ftot(ni), smean(ni)
      real(dp) :: asum(ni)
      integer :: j, i
      ftot = 0.0_dp
      smean = 0.0_dp
      asum = 0.0_dp
      do j = 1, size(st%s)
         i = cdef%pairs(j)%iface
         ftot(i) = ftot(i) + st%s(j)%ft
         if (st%s(j)%closed .and. cdef%pairs(j)%area > 0.0_dp) then
            smean(i) = smean(i) + cdef%pairs(j)%area*st%s(j)%ut
            asum(i) = asum(i) + cdef%pairs(j)%area
         end if
      end do
      where (asum > 0.0_dp) smean = smean/asum
   end subroutine interface_motion

   !> Double the history's room.
   subroutine grow(en)
      type(energy_t), intent(inout) :: en
      integer, allocatable :: st(:)
      real(dp), allocatable :: la(:, :), h(:, :, :)
      integer :: n
      n = ubound(en%step, 1)
      allocate (st(0:2*n + 1), la(size(en%lambda, 1), 0:2*n + 1), h(3, size(en%hist, 2), 0:2*n + 1))
      st(0:n) = en%step
      la(:, 0:n) = en%lambda
      h(:, :, 0:n) = en%hist
      call move_alloc(st, en%step)
      call move_alloc(la, en%lambda)
      call move_alloc(h, en%hist)
   end subroutine grow
end module contact_energy
