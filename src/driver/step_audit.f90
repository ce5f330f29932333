!> The checks that decide whether a run's numbers can be trusted.
!!
!! * Finite numbers: a NaN or Inf in a solution, a spring force or a stress
!!   (an overflowing load factor, modulus or roughness constant) stops the run
!!   as a numerical failure naming the increment; it is checked once where the
!!   numbers are formed: after every attempt at an increment (its displacement
!!   increment and spring forces) and in the fields of an accepted step.
!! * Doubts: an accepted step is doubtful when contact states were frozen
!!   after MAX_SWITCH mode changes (chatter), when the normal or the
!!   tangential spring forces left their law by more than DRIFT_LIMIT (the
!!   paper's explicit scheme: law_drift, tangential_drift), or
!!   when an invariant of SPEC §7 is violated (body equilibrium to 1e-8, no
!!   tension, |F_T| <= mu F_n, non-decreasing effective slip).  A run with a
!!   doubtful step ends "doubtful" (exit code 4), not "completed"; the pairs and
!!   increments concerned are named on the terminal, in the listing and in the
!!   result file.
!!
!! * History: the figures of every accepted step (run_history_t, which the
!!   driver's run result extends), kept in arrays that grow by doubling.
!!
!! Ref: SPEC §7 (invariants), §4.2 (drift of the explicit scheme).
module step_audit
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite, ieee_is_nan
   use kinds, only: dp, stderr
   use errors, only: status_t, STAT_NONFINITE, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa
   use records, only: step_record_t, body_fields_t, run_doubts_t, DRIFT_LIMIT, MAX_DOUBT_LINES, &
         STEP_CONVERGED, TS_SLIP
   use contact_types, only: contact_def_t, LAW_ROUGH
   use contact_laws, only: normal_pressure
   use contact_algorithm, only: contact_state_t, check_invariants, frozen_pairs, MAX_SWITCH
   use listing, only: list_sliding_warning
   use roundoff, only: resolvable_limit
   implicit none
   private
   public :: check_finite_attempt, check_finite_step, audit_step, note_doubts, doubt_summary, &
         pair_list, check_runaway, check_runaway_displacement
   public :: sliding_warning, check_finite_springs, run_history_t, IMBALANCE_NOT_COMPUTED, &
         imbalance_limit

   !> step%imbalance of a step whose body fields were not computed (its
   !! results are not written: OPTIONS RESULTS), so its equilibrium was not checked.
   real(dp), parameter :: IMBALANCE_NOT_COMPUTED = -1.0_dp
   !> A body out of equilibrium by more than this (relative to the force
   !! scale), beyond the round-off of its internal forces, makes a step doubtful.
   real(dp), parameter :: IMBALANCE_TOL = 1.0e-8_dp

   !> The body fields of the last step and the figures of every accepted
   !! step (one entry per step after `trim_history`; during the run the
   !! arrays grow by doubling and hold `nhist` entries).
   type, extends(body_fields_t) :: run_history_t
      integer :: nhist = 0                       !! steps held
      integer, allocatable :: iterations(:)      !! solves per increment
      integer, allocatable :: repeats(:)         !! repeats (mode changes) per increment
      real(dp), allocatable :: residual(:)       !! relative out-of-balance
                                                 !! force after each increment
      real(dp), allocatable :: drift(:)          !! largest departure of F_n
                                                 !! from its curve, relative
      real(dp), allocatable :: drift_t(:)        !! largest departure of F_T from
                                                 !! the tangential law, relative
      real(dp), allocatable :: imbalance(:)      !! largest force imbalance of a body, relative
                                                 !! (IMBALANCE_NOT_COMPUTED: a step not written)
      real(dp), allocatable :: imbalance_limit(:) !! the imbalance beyond which the step is doubtful
      integer, allocatable :: violations(:)      !! invariant violations per increment (SPEC §7)
      real(dp), allocatable :: penetration(:)    !! ideal contact: largest |u_n| (closed)
                                                 !! or stick slip at the end
      integer, allocatable :: augmentations(:)   !! ideal contact: multiplier updates per increment
   contains
      procedure :: append_history
      procedure :: trim_history
   end type run_history_t

contains

   !> Stop (STAT_NONFINITE) if an attempt at an increment produced a
   !! non-finite displacement increment or spring force.
   subroutine check_finite_attempt(du, st, has_contact, status)
      real(dp), intent(in) :: du(:, :)               !! (2, npoin) displacement increment
      type(contact_state_t), intent(in) :: st        !! current spring forces (contact models)
      logical, intent(in) :: has_contact
      type(status_t), intent(inout) :: status
      if (.not. status%ok()) return
      call check_nodal(du, 'displacement increment', status)
      if (.not. status%ok() .or. .not. has_contact) return
      if (allocated(st%fn)) call check_pairs(st%fn, 'normal spring force', status)
      if (allocated(st%ft) .and. status%ok()) then
         call check_pairs(st%ft, 'tangential spring force', status)
      end if
   end subroutine check_finite_attempt

   !> Stop (STAT_NO_CONVERGENCE) an attempt whose solution slid a closed pair by more than the
   !! model's largest extent.  The pairs assume small sliding (their partners stay opposite each
   !! other; a slide of 10 % of the pair spacing is warned about, sliding_warning), so such a
   !! solution is none of the method's: it is what a body held in some direction by friction
   !! alone does when its load exceeds what the friction can carry.  Every pair slips, the
   !! force-free regularising springs of the slipping pairs (or their round-off) are all that
   !! holds it, and the solution moves it by the out-of-balance force over those springs (a
   !! hub pushed off its shaft: 1.6e7 mm after one increment, "converged" because the
   !! round-off of a body moved that far swamps every criterion).  No static equilibrium
   !! exists; the run says so instead of accepting the motion, when some closed pair slips.
   !! (Checked on converged attempts:
   !! one that failed says why it failed, and its last iterate may be anywhere.)
   subroutine check_runaway(st, msize, step, status)
      type(contact_state_t), intent(in) :: st        !! the attempt's modes and increments
      real(dp), intent(in) :: msize                  !! the model's largest extent [length]
      integer, intent(in) :: step                    !! the step attempted
      type(status_t), intent(inout) :: status
      integer :: j, jmax, nclosed, nslip
      real(dp) :: ut, utmax
      if (.not. status%ok() .or. .not. allocated(st%md) .or. .not. allocated(st%dut)) return
      if (size(st%dut) /= size(st%md)) return
      jmax = 0
      utmax = 0.0_dp
      nclosed = 0
      nslip = 0
      do j = 1, size(st%md)
         if (.not. st%md(j)%closed) cycle
         nclosed = nclosed + 1
         if (st%md(j)%tstate == TS_SLIP) nslip = nslip + 1
         ut = abs(st%s(j)%ut + st%dut(j))
         if (ut > utmax) then
            utmax = ut
            jmax = j
         end if
      end do
      ! (without a slipping pair the body is held by sticking springs, however soft: a slide
      ! that large is then the law's overflow or its softness, which other checks name)
      if (jmax == 0 .or. nslip == 0 .or. .not. (utmax > msize)) return
      call status%set(STAT_NO_CONVERGENCE, 'in increment '//itoa(step)//' pair '//itoa(jmax)// &
                      ' slid '//rtoa(utmax)//', more than the model''s size ('//rtoa(msize)// &
                      '), with '//itoa(nslip)//' of '//itoa(nclosed)//' closed pairs slipping: '// &
                      'a body moves without bound -- its load exceeds what the friction of its '// &
                      'contact can carry, or a restraint is missing; a static analysis has no '// &
                      'equilibrium to find (the pairs assume small sliding: docs/contact.md)')
   end subroutine check_runaway

   !> Stop (STAT_NO_CONVERGENCE) a step of a contact model whose total displacement moves a
   !! node by more than RUNAWAY_SIZES times the model's largest extent, slip or none: a body
   !! whose contact opened or released at zero load and that nothing else holds is moved by
   !! the next load over the round-off of a matrix singular in its rigid-body mode (a gasket
   !! between two flanges unloaded to zero and reloaded: the upper flange 1.8e9 mm away, and
   !! every later increment "converged", its criterion scaled by forces of that size).
   !! Checked on the accepted step after check_finite_step, whose message names a law that
   !! overflows at such closures.
   subroutine check_runaway_displacement(disp, msize, step, status)
      real(dp), intent(in) :: disp(:, :)             !! (2, npoin) the total displacements
      real(dp), intent(in) :: msize                  !! the model's largest extent [length]
      integer, intent(in) :: step                    !! the step
      type(status_t), intent(inout) :: status
      real(dp), parameter :: RUNAWAY_SIZES = 10.0_dp
      integer :: j
      if (.not. status%ok() .or. size(disp) == 0) return
      if (.not. (maxval(abs(disp)) > RUNAWAY_SIZES*msize)) return
      j = maxloc(maxval(abs(disp), dim=1), dim=1)
      call status%set(STAT_NO_CONVERGENCE, 'in increment '//itoa(step)//' node '//itoa(j)// &
                      ' moved '//rtoa(maxval(abs(disp(:, j))))//', more than ten times the '// &
                      'model''s size ('//rtoa(msize)//'): a body moves without bound -- held '// &
                      'by nothing once its contact opened or released (a stack unloaded to '// &
                      'zero and loaded again), or a restraint is missing; a small-displacement '// &
                      'analysis has no answer there (docs/contact.md, "Checks on every run")')
   end subroutine check_runaway_displacement

   !> Stop (STAT_NONFINITE) if a spring stiffness of the current modes is not
   !! finite (the law's tangent at an overflowing pressure), before a
   !! factorization would call the system singular.
   subroutine check_finite_springs(st, status)
      type(contact_state_t), intent(in) :: st
      type(status_t), intent(inout) :: status
      if (.not. allocated(st%md)) return
      call check_pairs(st%md%kn, 'normal spring stiffness', status)
      if (status%ok()) call check_pairs(st%md%kt, 'tangential spring stiffness', status)
   end subroutine check_finite_springs

   !> Stop (STAT_NONFINITE) if the fields of an accepted step hold a
   !! non-finite number: displacements, reactions, stresses, the committed
   !! spring forces and closures, and the law's force at the closures (the
   !! drift: the law overflows where the closure is finite but huge).
   subroutine check_finite_step(body, st, has_contact, drift, full, status)
      type(body_fields_t), intent(in) :: body
      type(contact_state_t), intent(in) :: st
      logical, intent(in) :: has_contact
      real(dp), intent(in) :: drift                 !! the step's law drift (law_drift)
      logical, intent(in) :: full                   !! the body fields were computed
                                                    !! (else: contact only)
      type(status_t), intent(inout) :: status
      integer :: k
      if (full) call check_nodal(body%disp, 'displacement', status)
      if (status%ok() .and. full) call check_nodal(body%react, 'reaction', status)
      if (status%ok() .and. full .and. .not. all(ieee_is_finite(body%sig_gp))) then
         k = first_bad(reshape(body%sig_gp, [size(body%sig_gp)]))
         call status%set(STAT_NONFINITE, 'non-finite stress ('// &
                         text(body%sig_gp(mod(k - 1, 4) + 1, (k - 1)/4 + 1))// &
                         ') at Gauss point '//itoa((k - 1)/4 + 1)//'; '//cause())
      end if
      if (.not. status%ok() .or. .not. has_contact) return
      call check_pairs(st%s%fn, 'normal spring force', status)
      if (status%ok()) call check_pairs(st%s%ft, 'tangential spring force', status)
      if (status%ok()) call check_pairs(st%s%un, 'closure', status)
      if (status%ok()) call check_pairs(st%s%ut, 'tangential displacement', status)
      if (status%ok() .and. .not. ieee_is_finite(drift)) call &
            status%set(STAT_NONFINITE, 'the interface law '// &
         'overflows at the closures of the step (its pressure at a closure is not finite); '// &
         cause())
   end subroutine check_finite_step

   !> The invariants, frozen states and drift of an accepted step: sets
   !! step%violations, step%imbalance, step%frozen, step%doubts ('' if the
   !! step is sound) and step%converged (false for an unsettled or frozen
   !! step).
   subroutine audit_step(cdef, st, ve_old, imbalance, limit, has_contact, step, fscale)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st       !! committed states of the step
      real(dp), intent(in) :: ve_old(:)             !! effective slip before the step
      real(dp), intent(in) :: imbalance             !! largest body imbalance,
                                                    !! relative (body_imbalance)
      real(dp), intent(in) :: limit                 !! the imbalance beyond which it
                                                    !! is doubtful (imbalance_limit)
      logical, intent(in) :: has_contact
      type(step_record_t), intent(inout) :: step
      real(dp), intent(in), optional :: fscale      !! the run's force scale (largest
                                                    !! nodal force so far)
      integer :: nbad
      integer, allocatable :: bad(:), frozen(:)
      character(len=:), allocatable :: imsg, d

      nbad = 0
      allocate (character(len=0) :: imsg, d)
      allocate (bad(0), frozen(0))
      if (has_contact) then
         call check_invariants(st, ve_old, nbad, imsg, bad, fscale)
         frozen = frozen_pairs(cdef, st)
      end if
      if (nbad > 0) imsg = imsg//' (pairs'//pair_list(bad)//')'
      if (imbalance > limit) then
         nbad = nbad + 1
         if (len(imsg) > 0) imsg = imsg//'; '
         imsg = imsg//'a body is out of equilibrium by '//rtoa(imbalance)// &
               ' of the load (limit '//rtoa(limit)//')'
      end if
      step%imbalance = imbalance
      step%imbalance_limit = limit
      step%violations = nbad
      step%frozen = size(frozen)
      ! frozen modes end the iteration without meeting its criterion
      step%converged = step%status == STEP_CONVERGED .and. step%frozen == 0
      if (size(frozen) > 0) d = 'contact states frozen after '//itoa(MAX_SWITCH)// &
            ' mode changes (chatter) at '// &
                                itoa(size(frozen))//' pair(s):'//pair_list(frozen)
      if (has_contact .and. step%drift > DRIFT_LIMIT) then
         if (len(d) > 0) d = d//'; '
         d = d//'normal spring forces up to '//percent(step%drift)// &
               ' % off the interface law (limit '// &
             itoa(nint(100.0_dp*DRIFT_LIMIT))//' %; the most at pair '// &
             itoa(worst_drift_pair(cdef, st))//')'
      end if
      if (has_contact .and. step%drift_t > DRIFT_LIMIT) then
         if (len(d) > 0) d = d//'; '
         d = d//'tangential spring forces up to '//percent(step%drift_t)// &
               ' % of mu F_n off the tangential law (limit '// &
             itoa(nint(100.0_dp*DRIFT_LIMIT))//' %; the most at pair '//itoa(step%drift_t_pair)//')'
      end if
      if (nbad > 0) then
         if (len(d) > 0) d = d//'; '
         d = d//itoa(nbad)//' invariant violation(s): '//imsg
      end if
      step%doubts = d
   end subroutine audit_step

   !> Count a doubtful step in the run's doubts, keep its line and say so on
   !! unit u (the first MAX_DOUBT_LINES steps).
   subroutine note_doubts(doubts, step, u)
      type(run_doubts_t), intent(inout) :: doubts
      type(step_record_t), intent(in) :: step
      integer, intent(in) :: u                      !! unit of the warning (the error unit)
      if (.not. allocated(doubts%details)) doubts%details = ''
      if (.not. allocated(step%doubts)) return
      if (len(step%doubts) == 0) return
      doubts%steps = doubts%steps + 1
      if (doubts%first == 0) doubts%first = step%step
      if (step%frozen > 0) doubts%frozen = doubts%frozen + 1
      if (step%contact .and. max(step%drift, step%drift_t) > DRIFT_LIMIT) then
         doubts%drift = doubts%drift + 1
      end if
      if (step%violations > 0) doubts%violations = doubts%violations + 1
      if (doubts%steps <= MAX_DOUBT_LINES) then
         if (len(doubts%details) > 0) doubts%details = doubts%details//new_line('a')
         doubts%details = doubts%details//'increment '//itoa(step%step)//': '//step%doubts
         write (u, '(a)') 'kontakt2d: warning: increment '//itoa(step%step)//' is doubtful: '// &
               step%doubts
      end if
   end subroutine note_doubts

   !> One line for the result file's status and the terminal: how many steps
   !! of each kind, and the first.
   function doubt_summary(doubts, nstep) result(s)
      type(run_doubts_t), intent(in) :: doubts
      integer, intent(in) :: nstep                  !! steps completed
      character(len=:), allocatable :: s
      s = itoa(doubts%steps)//' of '//itoa(nstep)//' increment(s) doubtful ('
      if (doubts%frozen > 0) s = s//'frozen contact states in '//itoa(doubts%frozen)//', '
      if (doubts%drift > 0) s = s//'law drift over '//itoa(nint(100.0_dp*DRIFT_LIMIT))//' % in '// &
                                itoa(doubts%drift)//', '
      if (doubts%violations > 0) s = s//'invariant violations in '//itoa(doubts%violations)//', '
      s = s(1:len(s) - 2)//'); the first: increment '//itoa(doubts%first)
   end function doubt_summary

   !> " 3 5 9" (the first 20 of a list of pairs, then " ...").
   function pair_list(pairs) result(s)
      integer, intent(in) :: pairs(:)
      character(len=:), allocatable :: s
      integer :: k
      s = ''
      do k = 1, min(size(pairs), 20)
         s = s//' '//itoa(pairs(k))
      end do
      if (size(pairs) > 20) s = s//' ...'
   end function pair_list

   !> Warning when the method is used outside its comfort zone (once per
   !! run): a tangential relative displacement of a closed pair above 10 % of the pair spacing
   !! (node-to-node pairs assume small sliding: the partners must stay
   !! opposite each other; very soft roughness or a large tangential load
   !! breaks that).
   subroutine sliding_warning(st, spacing, step, warned, nwarn)
      type(contact_state_t), intent(in) :: st       !! committed states
      real(dp), intent(in) :: spacing(:)            !! (npair) distance to the nearest
                                                    !! other pair [length]
      integer, intent(in) :: step                   !! the step
      logical, intent(inout) :: warned              !! the warning was given (once per run)
      integer, intent(inout) :: nwarn               !! warnings of the run
      integer :: j
      if (warned) return
      do j = 1, size(st%s)
         ! an open pair's partners are not in contact: its tangential motion is no slip
         if (.not. st%s(j)%closed) cycle
         if (abs(st%s(j)%ut) > 0.1_dp*spacing(j)) then
            warned = .true.
            nwarn = nwarn + 1
            call list_sliding_warning(stderr, step, j, abs(st%s(j)%ut), spacing(j))
            return
         end if
      end do
   end subroutine sliding_warning

   ! ------------------------------------------------------------------ helpers

   !> The closed rough pair whose normal force is farthest from its law (the
   !! pair of law_drift's largest value; 0 if none is closed).
   pure integer function worst_drift_pair(cdef, st) result(jw)
      type(contact_def_t), intent(in) :: cdef
      type(contact_state_t), intent(in) :: st
      integer :: j
      real(dp) :: d, dmax
      jw = 0
      dmax = -1.0_dp
      do j = 1, size(st%s)
         associate (s => st%s(j), pr => cdef%pairs(j), ifc => cdef%ifaces(cdef%pairs(j)%iface))
            if (.not. s%closed .or. ifc%law /= LAW_ROUGH) cycle
            d = abs(s%fn - pr%area*normal_pressure(s%un, ifc%cn, ifc%m, ifc%cn2, ifc%m2, &
                                                   s%on_unloading, s%ua, s%pa))
            if (d > dmax) then
               dmax = d
               jw = j
            end if
         end associate
      end do
   end function worst_drift_pair

   !> A nodal field (2, npoin): name the first non-finite entry.
   subroutine check_nodal(v, what, status)
      real(dp), intent(in) :: v(:, :)
      character(len=*), intent(in) :: what
      type(status_t), intent(inout) :: status
      integer :: k
      if (all(ieee_is_finite(v))) return
      k = first_bad(reshape(v, [size(v)]))
      call status%set(STAT_NONFINITE, 'non-finite '//what//' ('// &
                      text(v(mod(k - 1, 2) + 1, (k - 1)/2 + 1))// &
                      ') at node '//itoa((k - 1)/2 + 1)//', dof '// &
                      merge('x', 'y', mod(k - 1, 2) == 0)//'; '//cause())
   end subroutine check_nodal

   !> A per-pair quantity: name the first pair with a non-finite value.
   subroutine check_pairs(v, what, status)
      real(dp), intent(in) :: v(:)
      character(len=*), intent(in) :: what
      type(status_t), intent(inout) :: status
      integer :: k
      if (all(ieee_is_finite(v))) return
      k = first_bad(v)
      call status%set(STAT_NONFINITE, 'non-finite '//what//' ('//text(v(k))// &
                      ') at contact pair '//itoa(k)// &
                      '; '//cause())
   end subroutine check_pairs

   pure integer function first_bad(v) result(k)
      real(dp), intent(in) :: v(:)
      do k = 1, size(v)
         if (.not. ieee_is_finite(v(k))) return
      end do
      k = 0
   end function first_bad

   !> Append the figures of an accepted step; the arrays double when full.
   pure subroutine append_history(h, step)
      class(run_history_t), intent(inout) :: h
      type(step_record_t), intent(in) :: step
      integer :: n
      if (.not. allocated(h%iterations)) call resize(h, 0, 16)
      if (h%nhist == size(h%iterations)) call resize(h, h%nhist, max(16, 2*h%nhist))
      n = h%nhist + 1
      h%iterations(n) = step%solutions
      h%repeats(n) = step%repeats
      h%residual(n) = step%residual
      h%drift(n) = step%drift
      h%drift_t(n) = step%drift_t
      h%penetration(n) = step%penetration
      h%augmentations(n) = step%augmentations
      h%imbalance(n) = step%imbalance
      h%imbalance_limit(n) = step%imbalance_limit
      h%violations(n) = step%violations
      h%nhist = n
   end subroutine append_history

   !> Cut the arrays to the steps held (at the end of the load history).
   pure subroutine trim_history(h)
      class(run_history_t), intent(inout) :: h
      call resize(h, h%nhist, h%nhist)
   end subroutine trim_history

   !> The history arrays with room for cap entries, the first n kept.
   pure subroutine resize(h, n, cap)
      class(run_history_t), intent(inout) :: h
      integer, intent(in) :: n, cap
      call grow_int(h%iterations)
      call grow_int(h%repeats)
      call grow_int(h%augmentations)
      call grow_int(h%violations)
      call grow_real(h%residual)
      call grow_real(h%drift)
      call grow_real(h%drift_t)
      call grow_real(h%penetration)
      call grow_real(h%imbalance)
      call grow_real(h%imbalance_limit)
   contains
      pure subroutine grow_int(a)
         integer, allocatable, intent(inout) :: a(:)
         integer, allocatable :: b(:)
         allocate (b(cap))
         b = 0
         if (n > 0) b(1:n) = a(1:n)
         call move_alloc(b, a)
      end subroutine grow_int
      pure subroutine grow_real(a)
         real(dp), allocatable, intent(inout) :: a(:)
         real(dp), allocatable :: b(:)
         allocate (b(cap))
         b = 0.0_dp
         if (n > 0) b(1:n) = a(1:n)
         call move_alloc(b, a)
      end subroutine grow_real
   end subroutine resize

   !> A fraction as a percentage with one decimal.
   function percent(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      if (abs(x) < 1.0e6_dp) then
         s = rtoa(100.0_dp*x, '(f0.1)')
      else
         s = 'more than 1E+08'        ! 100 x itself could overflow
      end if
   end function percent

   !> What a non-finite number is: not a number, +infinity or -infinity.
   pure function text(x) result(s)
      real(dp), intent(in) :: x
      character(len=:), allocatable :: s
      if (ieee_is_nan(x)) then
         s = 'not a number'
      else if (x > 0.0_dp) then
         s = '+infinity'
      else
         s = '-infinity'
      end if
   end function text

   pure function cause() result(s)
      character(len=:), allocatable :: s
      s = 'a number of the model is out of the range of double precision (a load factor, a &
      &modulus, '// &
          'a roughness constant c_n^m or an exponent): check the deck''s values and units'
   end function cause

   !> The largest relative imbalance of a body that is round-off, not an
   !! error: IMBALANCE_TOL raised by the round-off floor of the module
   !! roundoff (the definition Newton's test and the invariant checks share).
   !! A body's imbalance sums the out-of-balance forces of its equations, and
   !! equation i is resolved only to the round-off of the forces that cancel
   !! in it, the bodies' K u: about epsilon |K_i| |u| (Higham, 2nd ed., §3.5
   !! and §9.1), |K_i| |u| = |K_i| |u_i| where the body moves nearly as a
   !! whole (|K_i| the row's absolute sum, absrow).  Summed over the equations
   !! with random signs the magnitude is sqrt(sum_i (|K_i| u_i)^2).  For
   !! bodies of ordinary stiffness its round-off is far below 1e-8 of the
   !! loads; it counts where a nearly rigid body (E of 1e9 N/mm2 on a soft
   !! interface, say) moves by much more than it deforms, and K u cancels to
   !! the forces from numbers 1e7 times larger.
   pure real(dp) function imbalance_limit(absrow, id, disp, scale) result(limit)
      real(dp), intent(in) :: absrow(:)    !! (neq) absolute row sums of the bodies' stiffness
      integer, intent(in) :: id(:, :)      !! (2, npoin) equation of each dof (<= 0: restrained)
      real(dp), intent(in) :: disp(:, :)   !! (2, npoin) displacements of the step
      real(dp), intent(in) :: scale        !! the force scale the imbalance is relative to
      real(dp) :: s
      integer :: ip, idof
      s = 0.0_dp
      do ip = 1, min(size(id, 2), size(disp, 2))
         do idof = 1, 2
            if (id(idof, ip) > 0) s = s + (absrow(id(idof, ip))*disp(idof, ip))**2
         end do
      end do
      limit = resolvable_limit(IMBALANCE_TOL, scale, sqrt(s))
   end function imbalance_limit
end module step_audit
