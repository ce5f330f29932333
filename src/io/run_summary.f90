!> The summary that ends the listing and the terminal output of a run: what an
!! engineer reads first.
!!
!! One table of the load stages (the monotone pieces of the load history:
!! loading, unloading, holding, read from the deck's load factors) with their
!! increments, load factors, solutions and worst law drift; then the state of
!! the interface at the end of the run: peak pressure and where, contact width
!! and area, approach of the bodies, total normal and tangential force,
!! slipping pairs, the residual closure left by unloading, the worst law drift
!! of the run, the solutions and the time.
!!
!! It is fed from the records of the run (the body and contact fields of the
!! last step, the solutions and drifts of every step, the pairs' reversal
!! points) and the model; it computes in a pure routine (`summarise_run`) and
!! prints in another (`write_run_summary`).  `list_run_summary` is the one call
!! of the driver.
!!
!! Definitions (docs/results-format.md, "Run summary"):
!!
!! * approach: the relative displacement of the two bodies along the mean pair
!!   normal n (from body B into body A), between the points of each body
!!   farthest from the interface along n: delta = mean(u_B.n) - mean(u_A.n),
!!   positive when the bodies approach; a rigid body is its reference node.
!! * contact width: extent of the closed pairs along the interface coordinate
!!   (the coordinate along which the pairs spread most); area: the sum of
!!   their lumped areas A_j (ring areas in axisymmetry).
!! * residual closure: the permanent set max(u_A - c_n2 p_A^m2, 0) of the
!!   normal law after unloading from the reversal point A (SPEC D8; clamped at
!!   0 beyond the law's admissible range, docs/contact.md), largest over the
!!   pairs that were unloaded: a reversal point, and open or the pressure off
!!   p_A by more than UNLOADED_FRACTION p_A at the end.  A tangential cycle
!!   under held pressure moves the pairs off p_A by round-off only (1e-8; they
!!   reverse on it): the line is printed only when some pair was unloaded.
!! * unloading beyond the law's range: the pairs whose reversal pressure
!!   (the largest of the run: A moves only up) exceeds their interface's p*.
!!
!! Ref: J. Altenbach, R. Buczkowski, Inkrementelle Finite-Elemente
!!      Modellierung des 2D-Kontaktproblems, eqs. (2.1a), (2.1b) (normal law).
module run_summary
   use kinds, only: dp, i8, stdout
   use model, only: model_t
   use records, only: body_fields_t, contact_fields_t, NS_OPEN, TS_SLIP
   use contact_types, only: LAW_ROUGH, PAIR_RIGID, UNITS_MODEL
   implicit none
   private
   public :: run_summary_t, summarise_run, write_run_summary, list_run_summary, load_stages
   public :: estimate_peak_t, note_estimate_peak, stage_case
   public :: list_dissipation, write_dissipation

   !> A pair with a reversal point counts as unloaded when its pressure has
   !! left p_A by more than this fraction of it (or it is open): 100 times the
   !! round-off by which a solution moves the pressures of a held load (1e-8
   !! of p in tests/decks/contact/tangential_cycle.dat: the pairs of a stiff
   !! block on a soft interface reverse on it), far below any unloading a deck
   !! applies.
   real(dp), parameter, public :: UNLOADED_FRACTION = 1.0e-6_dp
   !> The estimate at the largest strain energy is printed too when the end's strain energy is
   !! below this fraction of it (a run unloaded, or partly: its relative error is then of a
   !! smaller field than the one the mesh was made for).
   real(dp), parameter, public :: PEAK_ENERGY_FRACTION = 0.5_dp

   !> The figures of the summary.
   !> The error estimate of the step with the largest strain energy of the run, kept by the run
   !! report as the steps are written (note_estimate_peak): a run unloaded to zero ends at a
   !! strain energy of round-off, whose relative error says nothing about the mesh.
   type :: estimate_peak_t
      integer :: step = 0                           !! its step (0: no step estimated yet)
      real(dp) :: energy_norm = 0.0_dp              !! ||u_h||_E there
      real(dp) :: estimated_error = 0.0_dp          !! its estimated error, fraction [-]
      integer, allocatable :: zone_pairs(:)         !! (niface) its contact zones, as
      real(dp), allocatable :: zone_width(:), zone_jump(:)  !! run_summary_t's
   end type estimate_peak_t

   type :: run_summary_t
      integer :: nstep = 0                          !! accepted steps
      integer :: icase = 1                          !! the load case whose factor the stages follow
      logical :: by_deck = .true.                   !! stages mapped onto steps
                                                    !! (no automatic increments)
      integer, allocatable :: first(:), last(:)     !! steps of each stage
      integer, allocatable :: direction(:)          !! +1 loading, -1 unloading, 0 holding
      real(dp), allocatable :: lam_from(:), lam_to(:)  !! load factor at the start
                                                       !! and end of each stage
      integer, allocatable :: solutions(:)          !! solutions of each stage
      real(dp), allocatable :: drift(:)             !! worst law drift of each stage
      integer :: solutions_total = 0
      real(dp) :: worst_drift = 0.0_dp              !! worst law drift of the run
      integer :: worst_drift_step = 0
      ! the interface at the end of the run
      logical :: contact = .false.
      integer :: npair = 0, nclosed = 0, nslip = 0
      integer :: peak_pair = 0                      !! pair of the peak pressure (0: none closed)
      real(dp) :: peak_pressure = 0.0_dp
      real(dp) :: peak_xy(2) = 0.0_dp
      real(dp) :: width = 0.0_dp, area = 0.0_dp
      real(dp) :: approach = 0.0_dp
      real(dp) :: force_n = 0.0_dp, force_t = 0.0_dp
      ! the same figures for each interface of the deck (their forces are not to be added: a
      ! bolt's head, nut and clamped faces each carry the preload); printed per interface when
      ! the model has several
      integer :: niface = 0
      integer, allocatable :: if_pairs(:), if_closed(:), if_slip(:), if_peak_pair(:)
      real(dp), allocatable :: if_peak(:), if_peak_x(:), if_peak_y(:), if_width(:), if_area(:)
      real(dp), allocatable :: if_approach(:), if_force_n(:), if_force_t(:)
      logical :: unloaded = .false.                 !! some pair was unloaded (residual
                                                    !! closure applies)
      integer :: nunloaded = 0                      !! pairs unloaded
      real(dp) :: residual_closure = 0.0_dp
      integer :: nbeyond = 0                        !! pairs whose reversal pressure
                                                    !! exceeds p* of their interface
      integer :: beyond_pair = 0                    !! the one farthest beyond (largest p_A / p*)
      real(dp) :: beyond_pa = 0.0_dp, beyond_pstar = 0.0_dp  !! its p_A and p*
      character(len=:), allocatable :: length_unit, stress_unit, force_unit
      character(len=:), allocatable :: estimate     !! the error estimate's line (''
                                                    !! if none), error_estimate_line
      ! the figures of that line and of the lines after the summary (the result file's /summary)
      logical :: estimated = .false.                !! the last step's body fields
                                                    !! hold an error estimate
      real(dp) :: estimated_error = 0.0_dp          !! its estimated error, fraction [-]
      integer, allocatable :: zone_pairs(:)         !! (niface) closed pairs of each contact zone
      real(dp), allocatable :: zone_width(:), zone_jump(:)  !! (niface) their width, pressure jump
      ! the estimate at the largest strain energy, when that is not the last step (peak_step 0
      ! otherwise): its line, its figures and the end's strain energy as a fraction of its own
      integer :: peak_step = 0
      character(len=:), allocatable :: peak_estimate
      real(dp) :: peak_error = 0.0_dp, peak_energy_ratio = 0.0_dp
      integer, allocatable :: peak_zone_pairs(:)
      real(dp), allocatable :: peak_zone_width(:), peak_zone_jump(:)
      real(dp), allocatable :: dissipated(:)        !! (niface) energy dissipated, cumulative ...
      real(dp), allocatable :: dissipated_normal(:), dissipated_tangential(:)  !! ... and its parts
      ! filled by the caller (run_report): the time, doubts, warnings, pretension sections
      real(dp) :: seconds = 0.0_dp                  !! wall time of the run when
                                                    !! the summary was made
      integer :: warnings = 0                       !! warnings printed about the method
      integer :: doubtful = 0                       !! doubtful increments (their
                                                    !! count by kind below)
      integer :: doubt_frozen = 0, doubt_drift = 0, doubt_violations = 0
      integer :: first_doubtful = 0                 !! the first doubtful increment
      character(len=:), allocatable :: doubts       !! the doubts' one-line summary ('' none)
      character(len=:), allocatable :: doubt_details   !! one line per doubtful increment ('' none)
      integer :: pretension_step = 0                !! the last increment with
                                                    !! section forces (0: none)
      real(dp), allocatable :: pretension_force(:), pretension_shortening(:)  !! (nsection) at it
   end type run_summary_t

contains

   !> The summary to the listing (when there is one) and the terminal (unless quiet).
   subroutine list_run_summary(m, body, cf, solutions, drift, ua, pa, have_lis, lu, quiet, t0, rate)
      type(model_t), intent(in) :: m                    !! the model
      type(body_fields_t), intent(in) :: body           !! body fields of the last step
      type(contact_fields_t), intent(in) :: cf          !! contact fields of the last step
                                                        !! (unallocated without contact)
      integer, intent(in) :: solutions(:)               !! solutions of every accepted step
      real(dp), intent(in) :: drift(:)                  !! law drift of every accepted step
      real(dp), intent(in) :: ua(:), pa(:)              !! (npair) reversal points A of
                                                        !! the pairs (0: never unloaded)
      logical, intent(in) :: have_lis                   !! a listing is written
      integer, intent(in) :: lu                         !! its unit
      logical, intent(in) :: quiet                      !! no terminal output
      integer(i8), intent(in) :: t0, rate               !! clock at the start of the run, its rate
      type(run_summary_t) :: s
      integer(i8) :: t1
      real(dp) :: seconds
      call system_clock(t1)
      seconds = real(t1 - t0, dp)/real(max(rate, 1_i8), dp)
      call summarise_run(m, body, cf, solutions, drift, ua, pa, s)
      if (have_lis) call write_run_summary(lu, s, seconds)
      if (.not. quiet) call write_run_summary(stdout, s, seconds)
   end subroutine list_run_summary

   !> The figures of the summary from the records of the run.
   pure subroutine summarise_run(m, body, cf, solutions, drift, ua, pa, s, peak)
      type(model_t), intent(in) :: m                    !! the model
      type(body_fields_t), intent(in) :: body           !! body fields of the last step (disp)
      type(contact_fields_t), intent(in) :: cf          !! contact fields of the last step
      integer, intent(in) :: solutions(:)               !! solutions of every accepted step
      real(dp), intent(in) :: drift(:)                  !! law drift of every accepted step
      real(dp), intent(in) :: ua(:), pa(:)              !! reversal points of the pairs
      type(run_summary_t), intent(out) :: s
      type(estimate_peak_t), intent(in), optional :: peak  !! the estimate at the largest
                                                           !! strain energy (note_estimate_peak)
      integer :: k, np
      real(dp) :: ures
      s%nstep = size(solutions)
      s%solutions_total = sum(solutions)
      if (size(drift) > 0) then
         s%worst_drift_step = maxloc(drift, 1)
         s%worst_drift = drift(s%worst_drift_step)
      end if
      call stage_table(m, solutions, drift, s)
      call unit_names(m, s)
      s%estimate = error_estimate_line(body, cf, s%length_unit)
      s%estimated = body%estimated
      if (s%estimated) s%estimated_error = body%estimated_error
      if (s%estimated .and. allocated(cf%zone_width)) then
         s%zone_width = cf%zone_width
         s%zone_pairs = cf%zone_pairs
         s%zone_jump = cf%zone_jump
      end if
      s%peak_estimate = ''
      if (present(peak) .and. s%estimated) then
         if (peak%step > 0 .and. &
             body%energy_norm**2 < PEAK_ENERGY_FRACTION*peak%energy_norm**2) then
            s%peak_step = peak%step
            s%peak_error = peak%estimated_error
            s%peak_energy_ratio = (body%energy_norm/peak%energy_norm)**2
            if (allocated(peak%zone_width)) then
               s%peak_zone_width = peak%zone_width
               s%peak_zone_pairs = peak%zone_pairs
               s%peak_zone_jump = peak%zone_jump
            end if
            s%peak_estimate = peak_estimate_line(s)
         end if
      end if
      if (allocated(cf%dissipated_energy)) then
         s%dissipated = cf%dissipated_energy
         call dissipation_parts(m, cf, s%dissipated_normal, s%dissipated_tangential)
      end if
      np = 0
      if (allocated(cf%pressure) .and. allocated(m%contact%pairs)) then
         np = min(size(cf%pressure), size(m%contact%pairs))
      end if
      s%contact = np > 0
      if (.not. s%contact) return
      call selection_figures(m, body, cf, np, spread(.true., 1, np), s%npair, s%nclosed, s%nslip, &
                             s%peak_pair, s%peak_pressure, s%peak_xy, s%width, s%area, &
                             s%approach, s%force_n, s%force_t)
      call per_interface(m, body, cf, np, s)
      associate (pairs => m%contact%pairs(1:np))
         do k = 1, min(np, size(ua), size(pa))
            if (pa(k) <= 0.0_dp) cycle
            associate (f => m%contact%ifaces(pairs(k)%iface))
               if (f%law /= LAW_ROUGH) cycle
               if (pa(k) > f%p_reversal_max) then
                  s%nbeyond = s%nbeyond + 1
                  if (s%beyond_pair == 0 .or. pa(k)/f%p_reversal_max > &
                        s%beyond_pa/max(s%beyond_pstar, tiny(1.0_dp))) then
                     s%beyond_pair = k
                     s%beyond_pa = pa(k)
                     s%beyond_pstar = f%p_reversal_max
                  end if
               end if
               ! unloaded: a reversal point, and open or its pressure moved off p_A by more than
               ! round-off (a pair that holds its pressure at A, e.g. under a tangential cycle, has
               ! lost no closure)
               if (cf%normal_state(k) /= NS_OPEN .and. abs(cf%pressure(k) - pa(k)) <= &
                     UNLOADED_FRACTION*pa(k)) then
                  cycle
               end if
               ! the permanent set, clamped at 0 beyond the law's range (contact_laws'
               ! residual_closure)
               ures = max(ua(k) - f%cn2*pa(k)**f%m2, 0.0_dp)
            end associate
            if (s%unloaded) ures = max(ures, s%residual_closure)
            s%residual_closure = ures
            s%unloaded = .true.
            s%nunloaded = s%nunloaded + 1
         end do
      end associate
   end subroutine summarise_run

   !> The stages of the load history of case s%icase (the case whose factor
   !! varies most) and their solutions and drifts.  Without automatic
   !! increments step i is deck increment i; with them the steps cannot be
   !! mapped onto the deck's increments from these records, and one row holds
   !! the whole run.
   pure subroutine stage_table(m, solutions, drift, s)
      type(model_t), intent(in) :: m
      integer, intent(in) :: solutions(:)
      real(dp), intent(in) :: drift(:)
      type(run_summary_t), intent(inout) :: s
      integer :: nst, k, n
      integer, allocatable :: first(:), last(:), dir(:)
      real(dp), allocatable :: lam(:)
      n = s%nstep
      s%icase = stage_case(m)
      if (allocated(m%lambda)) then
         allocate (lam(size(m%lambda, 2)))
         lam(:) = m%lambda(s%icase, :)
      else
         allocate (lam(n + 1))
         lam(:) = 0.0_dp
      end if
      s%by_deck = .not. m%autoinc .and. n <= size(lam) - 1
      if (s%by_deck) then
         call load_stages(lam(1:n + 1), first, last, dir)
      else
         first = [1]
         last = [n]
         dir = [0]
      end if
      nst = size(first)
      allocate (s%first(nst), s%last(nst), s%direction(nst), s%lam_from(nst), s%lam_to(nst), &
                s%solutions(nst), s%drift(nst))
      s%first = first
      s%last = last
      s%direction = dir
      do k = 1, nst
         s%solutions(k) = sum(solutions(first(k):last(k)))
         s%drift(k) = 0.0_dp
         if (last(k) >= first(k) .and. size(drift) >= last(k)) then
            s%drift(k) = maxval(drift(first(k):last(k)))
         end if
         if (s%by_deck) then
            s%lam_from(k) = lam(first(k))           ! lam(1) is the factor before increment 1
            s%lam_to(k) = lam(last(k) + 1)
         else
            s%lam_from(k) = lam(1)
            s%lam_to(k) = lam(min(size(lam), m%nincs + 1))
         end if
      end do
   end subroutine stage_table

   !> The load case the stages (and the terminal's load factor column) follow: the case whose
   !! factor varies most over the history (a preload held while a service load cycles: the
   !! service load's case); the first of equals.
   pure integer function stage_case(m) result(icase)
      type(model_t), intent(in) :: m
      icase = 1
      if (.not. allocated(m%lambda)) return
      if (m%ncase > 1 .and. size(m%lambda, 1) > 1) then
         icase = maxloc(maxval(m%lambda, 2) - minval(m%lambda, 2), 1)
      end if
   end function stage_case

   !> The monotone stages of a load history: lam(1) is the factor at the start,
   !! lam(i+1) after step i.  A stage ends where the factor turns (loading to
   !! unloading or back); steps that hold the factor join the stage before (or
   !! form the first stage if the history starts with them).
   pure subroutine load_stages(lam, first, last, dir)
      real(dp), intent(in) :: lam(:)                !! (nstep+1) load factors
      integer, allocatable, intent(out) :: first(:), last(:)  !! steps of each stage
      integer, allocatable, intent(out) :: dir(:)   !! +1 loading, -1 unloading, 0 holding
      integer :: i, n, d, cur
      real(dp) :: tol
      n = size(lam) - 1
      allocate (first(0), last(0), dir(0))
      if (n < 1) return
      tol = 1.0e-12_dp*max(1.0_dp, maxval(abs(lam)))
      first = [1]
      cur = 0
      do i = 1, n
         d = 0
         if (lam(i + 1) - lam(i) > tol) d = 1
         if (lam(i + 1) - lam(i) < -tol) d = -1
         if (d == 0 .or. d == cur) cycle
         if (cur /= 0) then
            last = [last, i - 1]
            first = [first, i]
         end if
         dir = [dir, d]
         cur = d
      end do
      if (size(dir) == 0) dir = [0]
      last = [last, n]
   end subroutine load_stages

   !> The interface figures of the summary for each interface of the deck (pairs%iface): the
   !! same definitions as the whole model's, over that interface's pairs alone.
   pure subroutine per_interface(m, body, cf, np, s)
      type(model_t), intent(in) :: m                    !! the model
      type(body_fields_t), intent(in) :: body           !! body fields of the last step (disp)
      type(contact_fields_t), intent(in) :: cf          !! contact fields of the last step
      integer, intent(in) :: np                         !! pairs with fields
      type(run_summary_t), intent(inout) :: s
      integer :: ni, i
      real(dp) :: xy(2)
      ni = 0
      if (allocated(m%contact%ifaces)) ni = size(m%contact%ifaces)
      ni = max(ni, maxval(m%contact%pairs(1:np)%iface))
      s%niface = ni
      allocate (s%if_pairs(ni), s%if_closed(ni), s%if_slip(ni), s%if_peak_pair(ni), source=0)
      allocate (s%if_peak(ni), s%if_peak_x(ni), s%if_peak_y(ni), s%if_width(ni), s%if_area(ni), &
                s%if_approach(ni), s%if_force_n(ni), s%if_force_t(ni), source=0.0_dp)
      do i = 1, ni
         call selection_figures(m, body, cf, np, m%contact%pairs(1:np)%iface == i, s%if_pairs(i), &
                                s%if_closed(i), s%if_slip(i), s%if_peak_pair(i), s%if_peak(i), &
                                xy, s%if_width(i), s%if_area(i), s%if_approach(i), &
                                s%if_force_n(i), s%if_force_t(i))
         s%if_peak_x(i) = xy(1)
         s%if_peak_y(i) = xy(2)
      end do
   end subroutine per_interface

   !> The interface figures of the summary over a selection of the pairs (all of them: the
   !! model's; those of one interface: its own): pairs, closed and slipping pairs, the peak
   !! pressure (pair 0: none closed) and where, the closed pairs' width and area, the approach
   !! of the bodies, the total forces.
   pure subroutine selection_figures(m, body, cf, np, sel, npair, nclosed, nslip, peak_pair, &
                                     peak, xy, width, area, approach, fn, ft)
      type(model_t), intent(in) :: m                    !! the model
      type(body_fields_t), intent(in) :: body           !! body fields of the last step (disp)
      type(contact_fields_t), intent(in) :: cf          !! contact fields of the last step
      integer, intent(in) :: np                         !! pairs with fields
      logical, intent(in) :: sel(:)                     !! (np) the pairs selected
      integer, intent(out) :: npair, nclosed, nslip, peak_pair
      real(dp), intent(out) :: peak, xy(2), width, area, approach, fn, ft
      integer :: j
      integer, allocatable :: idx(:)
      logical :: closed(np)
      peak_pair = 0
      peak = 0.0_dp
      xy = 0.0_dp
      width = 0.0_dp
      area = 0.0_dp
      approach = 0.0_dp
      associate (pairs => m%contact%pairs(1:np))
         closed = cf%normal_state(1:np) /= NS_OPEN
         npair = count(sel)
         nclosed = count(sel .and. closed)
         nslip = count(sel .and. closed .and. cf%tangential_state(1:np) == TS_SLIP)
         if (nclosed > 0) then
            peak_pair = maxloc(cf%pressure(1:np), 1, mask=sel .and. closed)
            peak = cf%pressure(peak_pair)
            xy = pairs(peak_pair)%position
            area = sum(pairs%area, mask=sel .and. closed)
            idx = pack([(j, j=1, np)], sel)
            width = closed_extent(pairs(idx), closed(idx))
         end if
         fn = sum(cf%force_normal(1:np), mask=sel)
         ft = sum(cf%force_tangential(1:np), mask=sel)
         if (allocated(body%disp) .and. npair > 0) approach = body_approach(m, body%disp, sel)
      end associate
   end subroutine selection_figures

   !> Extent of the closed pairs along the coordinate of largest spread of all pairs.
   pure real(dp) function closed_extent(pairs, closed) result(w)
      use contact_types, only: contact_pair_t
      type(contact_pair_t), intent(in) :: pairs(:)
      logical, intent(in) :: closed(:)
      integer :: ax, j
      real(dp) :: lo, hi, c
      ax = 1
      if (maxval(pairs%position(2)) - minval(pairs%position(2)) > &
          maxval(pairs%position(1)) - minval(pairs%position(1))) ax = 2
      lo = huge(1.0_dp)
      hi = -huge(1.0_dp)
      do j = 1, size(pairs)
         if (.not. closed(j)) cycle
         c = pairs(j)%position(ax)
         lo = min(lo, c)
         hi = max(hi, c)
      end do
      w = max(hi - lo, 0.0_dp)
   end function closed_extent

   !> Approach of the bodies (see the module header): bodies are the connected
   !! parts of the mesh; the far points of A and B along the mean pair normal.
   pure real(dp) function body_approach(m, disp, sel) result(delta)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: disp(:, :)            !! (2, npoin) displacements
      logical, intent(in) :: sel(:)                 !! the pairs to use (of the first
                                                    !! size(sel) pairs)
      integer :: body(m%npoin), j, ie, k, ra, r, np
      real(dp) :: n(2), s(m%npoin), tol, ext
      logical :: in_a(m%npoin), in_b(m%npoin)
      logical, allocatable :: use(:)
      np = min(size(m%contact%pairs), size(sel))
      allocate (use(np), source=sel(1:np))
      delta = 0.0_dp
      if (.not. any(use)) return
      associate (pairs => m%contact%pairs(1:np))
         ! connected parts of the mesh (union-find over the elements)
         ! (path halving keeps the trees flat: linear in practice; without it a mesh
         ! numbered along its length grows chains as long as the mesh, time quadratic)
         body = [(j, j=1, m%npoin)]
         do ie = 1, m%nelem
            call find(body, m%lnods(1, ie), ra)
            do k = 2, m%nnode_e(ie)
               call find(body, m%lnods(k, ie), r)
               if (r /= ra) body(r) = ra
            end do
         end do
         do j = 1, m%npoin
            call find(body, j, r)
            body(j) = r
         end do
         n = [sum(pairs%n(1), mask=use), sum(pairs%n(2), mask=use)]
         n = n/max(norm2(n), tiny(1.0_dp))
         s = n(1)*m%coord(1, :) + n(2)*m%coord(2, :)
         tol = 1.0e-6_dp*max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), &
                             maxval(m%coord(2, :)) - minval(m%coord(2, :)))
         ! the bodies (roots) of the A and B sides, then their nodes: O(npoin + npair)
         in_a = .false.
         in_b = .false.
         do j = 1, np
            if (.not. use(j)) cycle
            in_a(body(pairs(j)%node_a)) = .true.
            if (pairs(j)%kind /= PAIR_RIGID) in_b(body(pairs(j)%node_b)) = .true.
         end do
         in_a = in_a(body)
         in_b = in_b(body)
         ext = maxval(s, mask=in_a)
         in_a = in_a .and. s >= ext - tol
         if (all(pairs%kind == PAIR_RIGID .or. .not. use)) then
            in_b = .false.
            do j = 1, np
               if (use(j)) in_b(pairs(j)%nodes(2)) = .true.   ! the rigid body's reference node
            end do
         else
            ext = minval(s, mask=in_b)
            in_b = in_b .and. s <= ext + tol
         end if
         delta = sum(n(1)*disp(1, :) + n(2)*disp(2, :), mask=in_b)/max(count(in_b), 1) - &
                 sum(n(1)*disp(1, :) + n(2)*disp(2, :), mask=in_a)/max(count(in_a), 1)
      end associate
   contains
      !> Root of i's tree, halving the path on the way.
      pure subroutine find(parent, i, r)
         integer, intent(inout) :: parent(:)
         integer, intent(in) :: i
         integer, intent(out) :: r
         r = i
         do while (parent(r) /= r)
            parent(r) = parent(parent(r))
            r = parent(r)
         end do
      end subroutine find
   end function body_approach

   !> Unit names from the deck's unit convention: roughness constants in the
   !! literature's units (UNITS KGF_UM, N_UM) require the model in mm and N/mm2.
   pure subroutine unit_names(m, s)
      use model, only: NTYPE_PLANE_STRAIN, NTYPE_AXISYMMETRIC
      type(model_t), intent(in) :: m
      type(run_summary_t), intent(inout) :: s
      logical :: mm
      mm = .false.
      if (allocated(m%contact%ifaces)) then
         if (size(m%contact%ifaces) > 0) mm = m%contact%ifaces(1)%units /= UNITS_MODEL
      end if
      if (mm) then
         s%length_unit = 'mm'
         s%stress_unit = 'N/mm2'
         s%force_unit = 'N'
         if (m%ntype == NTYPE_PLANE_STRAIN) s%force_unit = 'N per mm of thickness'
         if (m%ntype == NTYPE_AXISYMMETRIC) s%force_unit = 'N (whole ring)'
      else
         s%length_unit = '(length)'
         s%stress_unit = '(stress)'
         s%force_unit = '(force)'
      end if
   end subroutine unit_names

   !> Print the summary on unit u.
   subroutine write_run_summary(u, s, seconds)
      integer, intent(in) :: u                      !! output unit
      type(run_summary_t), intent(in) :: s          !! the figures
      real(dp), intent(in) :: seconds               !! wall time of the run
      character(len=9), parameter :: dname(-1:1) = ['unloading', 'holding  ', 'loading  ']
      character(len=16) :: b
      integer :: k
      write (u, '(/a)') ' '//repeat('=', 78)
      write (u, '(a,i0,a)') ' SUMMARY OF THE RUN (load stages follow the factor of load case ', &
            s%icase, ')'
      write (u, '(a)') '  stage   increments      load factor from -> to  kind       solutions  &
      &worst drift'
      do k = 1, size(s%first)
         if (s%by_deck) then
            write (u, '(i7,i7,a,i6,2x,es12.4,a,es12.4,2x,a,i11,es13.3)') k, s%first(k), ' -', &
                  s%last(k), &
               s%lam_from(k), ' ->', s%lam_to(k), dname(s%direction(k)), s%solutions(k), s%drift(k)
         else
            write (u, '(i7,i7,a,i6,2x,a,i11,es13.3)') k, s%first(k), ' -', s%last(k), &
               'automatic increments: stages not separated', s%solutions(k), s%drift(k)
         end if
      end do
      if (s%contact .and. s%niface > 1) then
         ! several interfaces: each its own figures (their forces are not to be added)
         write (u, '(a,i0,a)') ' The interfaces at the end (increment ', s%nstep, '):'
         do k = 1, s%niface
            if (s%if_pairs(k) == 0) cycle
            write (u, '(a,i0)') '  interface ', k
            call write_interface_lines(u, '    ', s, s%if_peak_pair(k), s%if_peak(k), &
                                       [s%if_peak_x(k), s%if_peak_y(k)], s%if_width(k), &
                                       s%if_closed(k), s%if_pairs(k), s%if_area(k), &
                                       s%if_approach(k), s%if_force_n(k), s%if_force_t(k), &
                                       s%if_slip(k))
         end do
      else if (s%contact) then
         write (u, '(a,i0,a)') ' The interface at the end (increment ', s%nstep, '):'
         call write_interface_lines(u, '  ', s, s%peak_pair, s%peak_pressure, s%peak_xy, &
                                    s%width, s%nclosed, s%npair, s%area, s%approach, s%force_n, &
                                    s%force_t, s%nslip)
      end if
      if (s%contact) then
         if (s%unloaded) then
            write (u, '(a,es12.4,1x,a,a,i0,a)') '  residual closure    ', s%residual_closure, &
                  s%length_unit, &
               ' (permanent set after unloading: largest max(u_A - c_n2 p_A^m2, 0) of ', &
               s%nunloaded, ' pair(s))'
         end if
         if (s%nbeyond > 0) write (u, '(a,i0,a,i0,a,es12.4,a,es12.4,1x,a,a)') &
               '  unloading law        ', s%nbeyond, &
            ' pair(s) reversed beyond the law''s admissible range; the farthest: pair ', &
            s%beyond_pair, ', p_A ', &
            s%beyond_pa, ' > p*', s%beyond_pstar, s%stress_unit, ' (u_res taken as max(u_res, 0))'
         write (u, '(a,es12.4,a,i0,a)') '  worst law drift     ', s%worst_drift, ' (increment ', &
               s%worst_drift_step, ')'
      end if
      ! (followed by the estimate at the largest strain energy, the end's line says it is the
      ! end's: at zero load that of a residual field)
      if (len(s%estimate) > 0 .and. len(s%peak_estimate) > 0) then
         write (u, '(a,i0,a)') ' at the end (increment ', s%nstep, '):'//s%estimate
      else if (len(s%estimate) > 0) then
         write (u, '(a)') s%estimate
      end if
      if (len(s%peak_estimate) > 0) write (u, '(a)') s%peak_estimate
      write (b, '(f12.2)') seconds
      write (u, '(a,i0,a,i0,a)') ' ', s%solutions_total, ' solutions in ', s%nstep, &
            ' increments, '// &
         trim(adjustl(b))//' s'
      write (u, '(a)') ' '//repeat('=', 78)
   end subroutine write_run_summary

   !> The lines of one interface's state at the end (or of the model's one interface): peak
   !! pressure, contact width, approach, total forces, slipping pairs; each label padded to
   !! 22 characters with the indent so that the figures line up.
   subroutine write_interface_lines(u, ind, s, peak_pair, peak, xy, width, nclosed, npair, area, &
                                    approach, fn, ft, nslip)
      integer, intent(in) :: u                      !! output unit
      character(len=*), intent(in) :: ind           !! indent of the lines
      type(run_summary_t), intent(in) :: s          !! for the units
      integer, intent(in) :: peak_pair, nclosed, npair, nslip
      real(dp), intent(in) :: peak, xy(2), width, area, approach, fn, ft
      integer :: w
      w = 22 - len(ind)
      if (peak_pair > 0) then
         write (u, '(a,es12.4,1x,a,a,i0,a,es12.4,a,es12.4,a)') ind//lab('peak pressure'), peak, &
            s%stress_unit, ' at pair ', peak_pair, ' (', xy(1), ',', xy(2), ')'
      else
         write (u, '(a)') ind//lab('peak pressure')//' none: no pair is closed'
      end if
      write (u, '(a,es12.4,1x,a,a,i0,a,i0,a,es12.4,1x,a)') ind//lab('contact width'), width, &
         s%length_unit, ' (', nclosed, ' of ', npair, ' pairs closed), area', area, &
         s%length_unit//'2'
      write (u, '(a,es12.4,1x,a)') ind//lab('approach'), approach, s%length_unit
      write (u, '(a,es12.4,a,es12.4,1x,a)') ind//lab('total force normal'), fn, ', tangential', &
         ft, s%force_unit
      write (u, '(a,i0,a,i0,a)') ind//lab('slipping pairs')//' ', nslip, ' of ', nclosed, ' closed'
   contains
      pure function lab(t) result(r)
         character(len=*), intent(in) :: t
         character(len=w) :: r
         r = t
      end function lab
   end subroutine write_interface_lines

   !> The a posteriori error estimate of the last step in one line (docs/history.md):
   !! " estimated discretization error 3.14 % (energy norm); contact zone 4.100E+00 mm wide
   !! resolved by 9 pairs, largest pressure jump between neighbouring pairs 12.0 % of the peak"
   !! (one zone per interface with pairs); '' when the body fields hold no estimate.
   pure function error_estimate_line(body, cf, length_unit) result(line)
      type(body_fields_t), intent(in) :: body       !! body fields of the last step
      type(contact_fields_t), intent(in) :: cf      !! contact fields of the last step
      character(len=*), intent(in) :: length_unit   !! unit of length of the model
      character(len=:), allocatable :: line
      line = ''
      if (.not. body%estimated) return
      if (allocated(cf%zone_width)) then
         line = estimate_text(body%estimated_error, length_unit, cf%zone_width, cf%zone_pairs, &
                              cf%zone_jump)
      else
         line = estimate_text(body%estimated_error, length_unit)
      end if
   end function error_estimate_line

   !> The estimate at the largest strain energy of the run, after the last step's (when the run
   !! ended below it, e.g. unloaded): " at the largest strain energy (increment 23; the end's is
   !! 0.0 % of it): estimated discretization error 1.30 % (energy norm); contact zone ...".
   pure function peak_estimate_line(s) result(line)
      type(run_summary_t), intent(in) :: s
      character(len=:), allocatable :: line
      character(len=32) :: b, r
      write (b, '(i0)') s%peak_step
      write (r, '(f0.1)') 100.0_dp*s%peak_energy_ratio
      if (r(1:1) == '.') r = '0'//trim(r)
      line = ' at the largest strain energy (increment '//trim(b)//'; the end''s is '//trim(r)// &
             ' % of it):'
      if (allocated(s%peak_zone_width)) then
         line = line//estimate_text(s%peak_error, s%length_unit, s%peak_zone_width, &
                                    s%peak_zone_pairs, s%peak_zone_jump)
      else
         line = line//estimate_text(s%peak_error, s%length_unit)
      end if
   end function peak_estimate_line

   !> " estimated discretization error 3.14 % (energy norm)" and, given the contact zones,
   !! "; contact zone ... wide resolved by N pairs, largest pressure jump ..." per interface.
   pure function estimate_text(err, length_unit, zone_width, zone_pairs, zone_jump) result(line)
      real(dp), intent(in) :: err                   !! estimated error, fraction [-]
      character(len=*), intent(in) :: length_unit   !! unit of length of the model
      real(dp), intent(in), optional :: zone_width(:), zone_jump(:)  !! (niface)
      integer, intent(in), optional :: zone_pairs(:)                 !! (niface)
      character(len=:), allocatable :: line
      character(len=32) :: b
      integer :: k
      write (b, '(f0.2)') 100.0_dp*err
      if (b(1:1) == '.') b = '0'//trim(b)
      line = ' estimated discretization error '//trim(b)//' % (energy norm)'
      if (.not. (present(zone_width) .and. present(zone_pairs) .and. present(zone_jump))) return
      do k = 1, size(zone_width)
         if (size(zone_width) > 1) then
            write (b, '(i0)') k
            line = line//'; interface '//trim(b)//':'
         else
            line = line//';'
         end if
         if (zone_pairs(k) == 0) then
            line = line//' no pair closed'
            cycle
         end if
         write (b, '(es10.3)') zone_width(k)
         line = line//' contact zone '//trim(adjustl(b))//' '//length_unit//' wide resolved by '
         write (b, '(i0)') zone_pairs(k)
         line = line//trim(b)//merge(' pairs', ' pair ', zone_pairs(k) /= 1)
         write (b, '(f0.1)') 100.0_dp*zone_jump(k)
         if (b(1:1) == '.') b = '0'//trim(b)
         line = trim(line)//', largest pressure jump between neighbouring pairs '//trim(b)// &
               ' % of the peak'
      end do
   end function estimate_text

   !> Keep the estimate of a step whose body fields hold one if its strain energy is the largest
   !! so far (ties to the later step, so that a run held at its largest load keeps its end).
   pure subroutine note_estimate_peak(peak, step, body, cf)
      type(estimate_peak_t), intent(inout) :: peak
      integer, intent(in) :: step                   !! the step's number
      type(body_fields_t), intent(in) :: body       !! its body fields
      type(contact_fields_t), intent(in) :: cf      !! its contact fields (unallocated: none)
      if (.not. body%estimated) return
      if (peak%step > 0 .and. body%energy_norm < peak%energy_norm) return
      peak%step = step
      peak%energy_norm = body%energy_norm
      peak%estimated_error = body%estimated_error
      if (allocated(cf%zone_width)) then
         peak%zone_width = cf%zone_width
         peak%zone_pairs = cf%zone_pairs
         peak%zone_jump = cf%zone_jump
      else if (allocated(peak%zone_width)) then
         deallocate (peak%zone_width, peak%zone_pairs, peak%zone_jump)
      end if
   end subroutine note_estimate_peak

   !> The energy dissipated by the contact laws after the summary: per interface the cumulative
   !! total with its normal and tangential parts and, for a periodic history, the table of the
   !! load cycles (module contact_energy), to the listing (when there is one) and the terminal
   !! (unless quiet).  Nothing without contact.
   subroutine list_dissipation(m, cf, tab, have_lis, lu, quiet)
      use records, only: cycle_table_t
      type(model_t), intent(in) :: m
      type(contact_fields_t), intent(in) :: cf      !! contact fields of the last step
      type(cycle_table_t), intent(in) :: tab        !! the cycles of the run
      logical, intent(in) :: have_lis, quiet
      integer, intent(in) :: lu
      if (.not. allocated(cf%dissipated_energy)) return
      if (have_lis) call write_dissipation(lu, m, cf, tab)
      if (.not. quiet) call write_dissipation(stdout, m, cf, tab)
   end subroutine list_dissipation

   !> Print the dissipated energy and the cycle table on unit u.
   subroutine write_dissipation(u, m, cf, tab)
      use records, only: cycle_table_t
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(contact_fields_t), intent(in) :: cf
      type(cycle_table_t), intent(in) :: tab
      type(run_summary_t) :: s
      real(dp), allocatable :: dn(:), dt(:)
      integer :: i, ic
      call unit_names(m, s)
      write (u, '(a)') ' Energy dissipated by the contact laws, cumulative ('//s%force_unit// &
            ' x '//s%length_unit//'):'
      call dissipation_parts(m, cf, dn, dt)
      do i = 1, size(cf%dissipated_energy)
         write (u, '(a,i0,a,es12.4,a,es12.4,a,es12.4)') '  interface ', i, ': total', &
               cf%dissipated_energy(i), &
            ', normal hysteresis', dn(i), ', tangential (friction)', dt(i)
      end do
      if (tab%ncycle > 0) then
         write (u, '(a,i0,a)') ' Load cycles of the history: ', tab%ncycle, &
            ' (energy per cycle; amplitudes are half ranges of the interface''s total F_T and mean &
            &u_T)'
         write (u, '(a)') '  cycle  increments    iface      energy  F_T amplitude  slip &
         &amplitude' // &
            '  secant stiffness  loss factor  damping ratio'
         do ic = 1, tab%ncycle
            do i = 1, size(tab%energy, 1)
               if (.not. defined(i, ic)) then
                  ! the ratios of its mean slip are no joint's (contact.md, "Load cycles")
                  write (u, '(i7,i7,a,i6,i8,es12.4,es15.4,es16.4,a18,a13,a15)') ic, &
                     tab%first(ic), ' -', tab%last(ic), i, tab%energy(i, ic), &
                     tab%force_amplitude(i, ic), tab%slip_amplitude(i, ic), 'n/a', 'n/a', 'n/a'
                  cycle
               end if
               write (u, '(i7,i7,a,i6,i8,es12.4,es15.4,es16.4,es18.4,es13.4,es15.4)') ic, &
                     tab%first(ic), ' -', &
                  tab%last(ic), i, tab%energy(i, ic), tab%force_amplitude(i, ic), &
                  tab%slip_amplitude(i, ic), &
                  tab%secant_stiffness(i, ic), tab%loss_factor(i, ic), tab%damping_ratio(i, ic)
            end do
         end do
         if (allocated(tab%ratios_defined)) then
            if (.not. all(tab%ratios_defined)) write (u, '(a)') '  (n/a: the interface''s pairs &
               &do not move with its total force -- an ideal interface, or slips that cancel &
               &in the sum, as under a normal load cycle: no stiffness or damping of one joint)'
         end if
      end if
   contains
      !> The ratios of interface i in cycle ic are defined (a table without the flags: all).
      pure logical function defined(i, ic)
         integer, intent(in) :: i, ic
         defined = .true.
         if (allocated(tab%ratios_defined)) defined = tab%ratios_defined(i, ic)
      end function defined
   end subroutine write_dissipation

   !> The energy dissipated by the contact laws on each interface, split into its normal
   !! (hysteresis) and tangential (friction) parts: sums of the pairs' shares.
   pure subroutine dissipation_parts(m, cf, dn, dt)
      type(model_t), intent(in) :: m
      type(contact_fields_t), intent(in) :: cf      !! contact fields (dissipated_energy allocated)
      real(dp), allocatable, intent(out) :: dn(:), dt(:)   !! (niface) normal, tangential
                                                           !! [force x length]
      integer :: i, j
      allocate (dn(size(cf%dissipated_energy)), dt(size(cf%dissipated_energy)))
      do i = 1, size(cf%dissipated_energy)
         dn(i) = 0.0_dp
         dt(i) = 0.0_dp
         do j = 1, min(size(m%contact%pairs), size(cf%dissipation_normal))
            if (m%contact%pairs(j)%iface /= i) cycle
            dn(i) = dn(i) + cf%dissipation_normal(j)
            dt(i) = dt(i) + cf%dissipation_tangential(j)
         end do
      end do
   end subroutine dissipation_parts
end module run_summary
