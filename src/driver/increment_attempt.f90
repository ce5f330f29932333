!> What the increment loop works with (analysis_t), one attempt at an
!! increment (attempt_increment: solve, evaluate the springs, repeat until they
!! keep their modes and balance) and what it leaves (nothing committed yet),
!! and the messages of an attempt
!! that failed: one that did not converge names the criterion that failed
!! with its value and tolerance, and advises only what is not already in use;
!! a singular system names the node and dof.
module increment_attempt
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: status_t, STAT_NO_CONVERGENCE, STAT_SINGULAR
   use strings, only: itoa, rtoa
   use dof_map, only: dof_map_t
   use linear_solver, only: linear_solver_t
   use contact_system, only: contact_system_t
   use assembly, only: coupling_t, load_increment
   use contact_assembly, only: contact_springs_t
   use contact_types, only: contact_options_t, contact_pair_t
   use contact_algorithm, only: contact_state_t, begin_increment, evaluate_pairs, &
         augment_multipliers, early_update, &
                                drop_regularisation, regularise_slip, &
                                anchor_regularisation, release_anchors, settle_frozen, &
                                open_held_tension, hold_at_rest, start_rest, rest_active_set, &
                                end_rest, TS_SLIP
   use contact_start, only: increment_pressure, separating_load
   use model, only: model_t
   use step_audit, only: check_finite_springs
   use roundoff, only: resolvable_limit
   use pretension_assembly, only: pretension_run_t
   use increment_predictor, only: increment_predictor_t
   implicit none
   private
   public :: analysis_t, attempt_t, attempt_failure, describe_singular, out_of_balance, &
         attempt_increment

   !> Everything the increment loop works with.
   type :: analysis_t
      type(dof_map_t) :: map
      class(linear_solver_t), allocatable :: solver  !! the bodies' solver, until
                                                     !! the contact system takes it
      class(contact_system_t), allocatable :: sys    !! the system the increments solve
      type(contact_springs_t) :: springs             !! equations and matrices of the pairs' springs
      type(coupling_t) :: coup
      real(dp), allocatable :: fcase(:, :, :)      !! (2, npoin, ncase) forces at factor 1
      real(dp), allocatable :: ucase(:, :, :)      !! (2, npoin, ncase) prescribed
                                                   !! displacements at factor 1
      real(dp), allocatable :: diag(:)             !! (neq) diagonal of K_AB
      real(dp), allocatable :: absrow(:)           !! (neq) sum of |k_ij| of K_AB's row (its forces'
                                                   !! round-off, roundoff)
      logical, allocatable :: restrained(:, :)     !! (2, npoin)
      integer :: npair = 0
      integer :: maxrep = 30                       !! cap on solutions of one increment
      logical :: has_contact = .false.
      logical :: returning = .false.               !! RETURN update (Newton)
      logical :: modified = .false.                !! modified Newton: stiffness
                                                   !! kept within an increment
      logical :: system_current = .false.          !! the system holds the springs
                                                   !! of the current modes
      logical :: pending = .false.                 !! the recovery of the full
                                                   !! field of steps is postponed
      real(dp), allocatable :: kref(:, :, :)       !! (nd, nd, npair) reference
                                                   !! springs (contact_system)
      real(dp), allocatable :: spacing(:)          !! (npair) distance to the nearest other pair
      real(dp), allocatable :: tlaw(:, :)          !! (3, npair) the tangential
                                                   !! law along the committed
                                                   !! history (contact_algorithm's tangential_drift)
      integer, allocatable :: body(:, :)           !! (2, npoin) body of each node,
                                                   !! x and y (equilibrium check)
      integer :: nbody = 0
      real(dp) :: force_scale = tiny(1.0_dp)       !! largest nodal force seen so far
      logical :: warned_closure = .false.
      type(pretension_run_t) :: pret               !! pretension sections: spring stiffnesses
                                                   !! (pretension_assembly)
      type(increment_predictor_t) :: pred          !! the first iterate from the last increment
   end type analysis_t


   !> Outcome of one attempt at an increment (nothing committed yet).
   type :: attempt_t
      real(dp), allocatable :: du(:, :)            !! displacement increment
      real(dp), allocatable :: carry(:)            !! out-of-balance force left, free equations
      integer :: solutions = 0                     !! linear solutions
      integer :: repeats = 0                       !! solutions caused by mode changes
      logical :: converged = .false.
      logical :: changing = .false.                !! springs still changed their modes at the end
      real(dp) :: rnorm = 0.0_dp                   !! relative out-of-balance force
      real(dp) :: rtol = 0.0_dp                    !! the limit of rnorm: TOLR raised by the
                                                   !! round-off floor (roundoff)
      real(dp) :: fscale = 0.0_dp                  !! the force the out-of-balance
                                                   !! force was measured against
      real(dp) :: dnorm = 0.0_dp                   !! last correction relative
                                                   !! to the increment (Newton)
      real(dp) :: duscale = 0.0_dp                 !! largest displacement increment of a converged
                                                   !! attempt that was not a hold (the scale of a
                                                   !! hold's corrections)
      real(dp), allocatable :: utot(:, :)          !! (2, npoin) the displacements of the
                                                   !! converged attempts before this one (the
                                                   !! committed total, at least; out_of_balance)
      integer :: nchanged = 0                      !! pairs that changed their
                                                   !! mode in the last solution
      integer :: first_changed = 0                 !! the first of them
      logical :: loaded = .false.                  !! the external forces are not zero
                                                   !! (attempt_failure's diagnosis)
   end type attempt_t

   !> What a Newton solution started from, for the line search (line_search).
   type :: step_start_t
      real(dp), allocatable :: du(:, :)            !! the attempt's increment before the solve
      real(dp), allocatable :: rhs(:)              !! the out-of-balance force it solved for
      real(dp), allocatable :: rvec(:, :)          !! the pairs' forces it started from
      type(contact_state_t) :: st                  !! the pairs' modes and forces there
      real(dp) :: rnorm = 0.0_dp                   !! its relative out-of-balance force
   end type step_start_t

   !> A Newton solution whose out-of-balance force grows by more than this
   !! factor, no pair changing its mode, is shortened (line_search).
   real(dp), parameter :: LS_GROWTH = 2.0_dp
   integer, parameter :: LS_HALVINGS = 8           !! shortest step 2^-8 of the solution

contains

   !> The status of an attempt that ended without convergence: a Newton
   !! (RETURN) or ideal-contact increment out of balance, or springs still
   !! changing their modes, is a failure (STAT_NO_CONVERGENCE); an EXPLICIT
   !! increment whose slip forces have not settled is accepted (its
   !! out-of-balance force is carried into the next increment) and leaves the
   !! status alone.  The criteria, in the order they are checked: states still
   !! changing; the ideal pairs' penetration or stick slip (TOL of AUGMENTED);
   !! the out-of-balance force (CONVERGE TOLR); the last correction (TOLU).
   subroutine attempt_failure(att, st, opts, returning, autoinc, maxrep, inc, status)
      type(attempt_t), intent(in) :: att
      type(contact_state_t), intent(in) :: st
      type(contact_options_t), intent(in) :: opts
      logical, intent(in) :: returning          !! Newton update of the rough pairs
      logical, intent(in) :: autoinc            !! automatic increments in use
      integer, intent(in) :: maxrep             !! the cap on solutions of the run
      integer, intent(in) :: inc                !! the increment, for the message
      type(status_t), intent(inout) :: status
      character(len=:), allocatable :: what, advice
      integer :: nclosed
      if (att%converged) return
      advice = '; reduce the increment size'
      if (.not. autoinc) advice = advice//', use OPTIONS AUTOINC'
      advice = advice//' or raise CONTACT REPEATS (now '//itoa(maxrep)//')'
      if (att%changing) then
         what = 'the contact states still change ('//itoa(att%nchanged)// &
               ' pair(s) in the last solution, '// &
                'the first pair '//itoa(att%first_changed)//')'
      else if (.not. (returning .or. st%has_ideal)) then
         if (.not. st%chatter) return
         what = 'the contact states kept changing'
      else if (st%has_ideal .and. att%rnorm <= 1.0e-8_dp .and. st%violation > st%tol_pen) then
         what = 'ideal contact still penetrates or slips by '//rtoa(st%violation)// &
               ' > the tolerance '// &
                rtoa(st%tol_pen)//' (AUGMENTED TOL) after '//itoa(st%augmentations)// &
                ' multiplier updates'
         advice = advice//' or the AUGMENTED factor'
      else if (att%rnorm > max(att%rtol, opts%tol_residual)) then
         what = 'the relative out-of-balance force '//rtoa(att%rnorm)//' > the tolerance '// &
                rtoa(opts%tol_residual)//' (CONTACT CONVERGE TOLR)'
         if (att%rtol > opts%tol_residual*(1.0_dp + 1.0e-3_dp)) what = what//' raised to '// &
               rtoa(att%rtol)// &
            ' by the round-off of the forces that cancel in it'
      else if (returning .and. att%dnorm > opts%tol_displacement) then
         what = 'the last displacement correction '//rtoa(att%dnorm)// &
               ' of the increment > the tolerance '// &
                rtoa(opts%tol_displacement)//' (CONTACT CONVERGE TOLU)'
      else
         what = 'ideal contact: slipping pairs still off mu F_n after '//itoa(st%augmentations)// &
                ' multiplier updates'
      end if
      ! (a pair the guard froze in its mode: said beside the criterion that failed)
      if (st%chatter) what = what//'; a pair changed its state 6 times within the '// &
                             'increment and was held in its mode (chatter)'
      ! (every closed pair slipping at the end of a loaded increment: the likeliest cause, said
      ! beside it)
      if (allocated(st%md) .and. att%loaded) then
         nclosed = count(st%md%closed)
         if (nclosed > 0 .and. count(st%md%closed .and. st%md%tstate == TS_SLIP) == nclosed) then
            what = what//'; every closed pair slips at the end ('//itoa(nclosed)//' of '// &
                   itoa(nclosed)//'): a load that is a force may exceed what the contact''s '// &
                   'friction can carry, or a restraint is missing'
         end if
      end if
      call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                      itoa(att%solutions)//' solutions: '//what//advice)
   end subroutine attempt_failure

   !> The out-of-balance force of the last solution, relative to fscale
   !! (att%rnorm), and the limit it is held to (att%rtol): the tolerance
   !! TOLR raised by the round-off of what cancels in it (module roundoff).
   !! The out-of-balance force lives on the contact equations (rhs: the
   !! spring forces the solution predicted minus the actual ones), but it
   !! inherits the round-off of the solution: the bodies' forces K du of the
   !! increment are resolved only to about epsilon |K| |du|, and the forces
   !! of the whole history to epsilon |K| |u|: the increments' solutions each
   !! balance their loads against K du to round-off, so the spring forces of
   !! the total state balance K u only to the round-off of the total (which
   !! the equilibrium audit's floor measures too, step_audit's imbalance_limit).
   !! The magnitude that cancels at a contact dof is |K_i| max(|du_i|, |u_i|)
   !! (|K_i| the row's absolute sum, absrow; u = att%utot + du the total
   !! displacement, when att%utot is kept) plus the spring forces there; the
   !! largest over the pairs' dofs is the magnitude.  For bodies of ordinary
   !! stiffness its round-off is 1e-15 to 1e-12 of the load increment, and
   !! rtol is TOLR; at a zero-load increment of a stiff body held by soft
   !! pairs the total is what cancels (generated scene 21).
   pure subroutine out_of_balance(an, pairs, rhs, rvec, fscale, tol, att)
      type(analysis_t), intent(in) :: an
      type(contact_pair_t), intent(in) :: pairs(:)
      real(dp), intent(in) :: rhs(:)              !! (neq) out-of-balance force
      real(dp), intent(in) :: rvec(:, :)          !! (nd, npair) spring forces of the pairs
      real(dp), intent(in) :: fscale              !! the force rnorm is relative to
      real(dp), intent(in) :: tol                 !! CONTACT CONVERGE TOLR
      type(attempt_t), intent(inout) :: att       !! du in, rnorm and rtol out
      real(dp) :: mag, u
      integer :: j, k, ieq, ip
      logical :: total
      att%rnorm = 0.0_dp
      att%rtol = tol
      if (size(rhs) == 0) return
      att%rnorm = maxval(abs(rhs))/fscale
      mag = 0.0_dp
      total = allocated(att%utot)
      if (total) total = all(shape(att%utot) == shape(att%du))
      if (allocated(an%absrow) .and. allocated(an%springs%peq)) then
         do j = 1, size(pairs)
            do k = 1, 2*pairs(j)%nn
               ieq = an%springs%peq(k, j)
               if (ieq <= 0) cycle
               ip = pairs(j)%nodes((k + 1)/2)
               u = abs(att%du(2 - mod(k, 2), ip))
               if (total) u = max(u, abs(att%du(2 - mod(k, 2), ip) + att%utot(2 - mod(k, 2), ip)))
               mag = max(mag, an%absrow(ieq)*u + abs(rvec(k, j)))
            end do
         end do
      end if
      ! (a non-finite force or stiffness raises nothing: the checks of the finite numbers name it)
      if (ieee_is_finite(mag)) att%rtol = resolvable_limit(tol, fscale, mag)
   end subroutine out_of_balance

   !> Name the node and dof of a singular equation in the message.
   subroutine describe_singular(an, status)
      type(analysis_t), intent(in) :: an
      type(status_t), intent(inout) :: status
      integer :: ieq, k
      character(len=:), allocatable :: detail
      if (status%code /= STAT_SINGULAR) return
      ieq = an%sys%failed_equation()
      if (ieq <= 0) return
      ! keep the solver's pivot figures, name the node and dof instead of the equation
      k = index(status%message, ': ')
      detail = status%message(k + 1:)
      if (k > 0) detail = status%message(k + 2:)
      status%message = 'singular or unrestrained model at '//an%map%describe(ieq)//': '//detail
      if (an%has_contact) status%message = status%message// &
            '; a body held only by contact springs '// &
                                           'has no support once they open (normal) or slip &
                                           &(tangential)'
   end subroutine describe_singular

   !> A singular system with every contact pair open under a load that pulls
   !! the bodies apart is no failure of the method: a body that only the contact
   !! held has no equilibrium (a tensile load on a body resting on another, or a
   !! load factor taken below zero: the factors of INCREMENTS are the total
   !! targets of the load cases, not their increments).  The message says so,
   !! with the resultant that pulls (more than 1e-6 of the largest nodal force of
   !! the run: at zero load the resultant is round-off, and the failure is the
   !! zero-load class, docs/robustness.md).
   subroutine lift_off(m, st, fext, force_scale, status)
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: fext(:, :)      !! (2, npoin) the loads at the end of the increment
      real(dp), intent(in) :: force_scale     !! the largest nodal force of the run so far
      type(status_t), intent(inout) :: status
      real(dp) :: fsep
      if (size(st%md) == 0) return
      if (any(st%md%closed)) return
      fsep = separating_load(m, fext)
      ! (a resultant within 1e-6 of the run's forces is round-off of a zero load, no pull)
      if (.not. (fsep > 1.0e-6_dp*force_scale)) return
      status%message = status%message//'; every contact pair is open: the loads pull the '// &
                       'bodies apart (resultant '//rtoa(fsep)//' along the contact normal, '// &
                       'away from the other side) and nothing else holds them, so no '// &
                       'equilibrium exists (the factors of INCREMENTS are the total targets '// &
                       'of the load cases, not their increments: a load unloaded to zero has '// &
                       'the target 0)'
   end subroutine lift_off

   !> One attempt at an increment of the load factors dlam from the committed
   !! state: solve, check the springs, repeat until they keep their modes and
   !! balance (or the cap).  Nothing is committed here; the contact system
   !! gives the solution at the contact equations (at least), `recover` the
   !! full increment once the attempt is accepted.
   !!
   !! Rough pairs with the Newton update: an attempt whose system turns
   !! singular is made once more from the committed state with every pair in
   !! slip keeping K_T^e in the solve, a regularising spring that carries no
   !! force (contact_algorithm's regularise_slip): a body held only by the
   !! contact and a restraint against translation loses its rotational support
   !! when the pairs still closed slip (K_T = 0) and only one of them is left, as
   !! the pairs open one after another on an unloading to zero.  The solutions
   !! of both passes are counted; if the second does not converge either, the
   !! attempt fails with the singular system of the first (a body that nothing
   !! holds, every pair slipping, keeps that message).  In the second pass, once
   !! the out-of-balance force is within its limit but the correction is not,
   !! the regularising springs are anchored (contact_algorithm's
   !! anchor_regularisation: they carry the force they predict from there on) and
   !! released before the converged pass's force is checked once more.
   subroutine attempt_increment(an, m, st, dlam, carry, fext_new, first, att, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:), carry(:), fext_new(:, :)
      logical, intent(in) :: first
      type(attempt_t), intent(inout) :: att
      type(status_t), intent(inout) :: status
      type(status_t) :: singular
      integer :: spent
      att%loaded = maxval([0.0_dp, abs(fext_new)]) > 1.0e-12_dp*an%force_scale
      call attempt_pass(an, m, st, dlam, carry, fext_new, first, .false., att, status)
      if (status%code == STAT_SINGULAR .and. an%has_contact) then
         call lift_off(m, st, fext_new, an%force_scale, status)
      end if
      if (status%code /= STAT_SINGULAR .or. .not. (an%has_contact .and. an%returning .and. &
                                                   st%has_rough)) then
         return
      end if
      spent = att%solutions
      singular = status
      status = status_t()
      call attempt_pass(an, m, st, dlam, carry, fext_new, first, .true., att, status)
      att%solutions = att%solutions + spent
      ! no equilibrium with the regularising springs either (a body that really is
      ! free: every pair slipping with nothing else holding it): the singular system
      ! is the diagnosis, with its node and dof
      if (.not. (status%ok() .and. att%converged)) status = singular
   end subroutine attempt_increment

   !> One pass of attempt_increment; slip_reg: every pair in slip keeps K_T^e.
   subroutine attempt_pass(an, m, st, dlam, carry, fext_new, first, slip_reg, att, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:), carry(:), fext_new(:, :)
      logical, intent(in) :: first
      logical, intent(in) :: slip_reg            !! every pair in slip keeps K_T^e (regularise_slip)
      type(attempt_t), intent(inout) :: att
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: rhs(:), ddu(:, :), rvec(:, :), rpred(:, :), dl(:, :)
      logical, allocatable :: changed(:), wasc(:)
      integer :: iter, maxit, nrest, rest
      real(dp) :: fscale, dnorm, rshare, rprev
      logical :: need_matrix, done, again, newton, hold, anchored, shortened, fit_scale
      type(step_start_t) :: start
      allocate (rhs(an%map%neq), ddu(2, m%npoin), rvec(an%springs%nd, an%npair), &
                rpred(an%springs%nd, an%npair), &
                changed(an%npair), wasc(an%npair))
      rvec = 0.0_dp
      rpred = 0.0_dp
      if (.not. allocated(att%du)) then
         allocate (att%du(2, m%npoin), att%carry(an%map%neq), att%utot(2, m%npoin))
         att%du = 0.0_dp
         att%utot = 0.0_dp
      end if
      ! the total displacement so far: a converged attempt's increment (the full field once
      ! the step was accepted) joins it (one converged but not accepted, a step cut for
      ! chatter, raises the round-off floor a little: a bound, not a result)
      if (att%converged) att%utot = att%utot + att%du
      att%du = 0.0_dp
      att%solutions = 0
      att%repeats = 0
      att%converged = .false.
      att%changing = .false.
      att%rnorm = 0.0_dp
      st%chatter = .false.
      newton = an%returning .and. st%has_rough
      att%dnorm = 0.0_dp
      hold = .false.
      anchored = .false.
      rshare = 0.0_dp
      nrest = 0
      rest = 0
      rprev = 0.0_dp
      fit_scale = .false.
      call load_increment(an%coup, an%map, an%fcase, an%ucase, an%restrained, dlam, carry, rhs, &
                          att%du)
      fscale = max(maxval([0.0_dp, abs(rhs)]), maxval(abs(fext_new)), 1.0e-300_dp)
      ! spring forces and modes at the start of the increment
      if (an%has_contact) then
         ! the pressure a reload from zero force is expected to bring (0: none)
         if (.not. first .and. st%has_rough) call increment_pressure(m, an%fcase, dlam, st)
         call begin_increment(m%contact, st, first)
         if (slip_reg) call regularise_slip(m%contact, st)
         call an%springs%start_forces(m%contact, st, rvec, rpred, rhs)
         call an%pred%predict(an%springs, m%contact, st, dlam, first .or. slip_reg, &
                              an%restrained, att%du, rvec, rhs)
      end if

      call an%sys%begin_attempt()
      ddu = att%du       ! first solve: prescribed increments at the restrained dofs
      need_matrix = an%has_contact .or. .not. an%system_current
      maxit = merge(an%maxrep, 1, an%has_contact)
      do iter = 1, maxit
         ! half the solutions spent: the modes' own stiffnesses (no regularising springs)
         if (an%has_contact .and. iter == maxit/2 + 1 .and. .not. st%regularise_slip) then
            call drop_regularisation(m%contact, st, need_matrix)
         end if
         if (need_matrix) then
            call set_system(an, m, st, status)
            if (.not. status%ok()) return
         end if
         if (iter == 1) then
            call an%springs%subtract_prescribed(m%contact%pairs, ddu, rhs)
            call first_force_scale(an, st, att, rhs, carry, fext_new, slip_reg, fscale, hold, &
                                   fit_scale)
         end if
         if (newton .and. iter > 1) call keep_start(att, st, rhs, rvec, start)
         ! the solution at (at least) the contact equations' dofs
         call an%sys%solve(rhs, ddu, status)
         if (.not. status%ok()) then
            call describe_singular(an, status)
            return
         end if
         att%solutions = iter
         if (iter == 1) call an%pred%shift_first(ddu)
         att%du = att%du + merge(0.0_dp, ddu, an%restrained)
         if (.not. an%has_contact) then
            att%converged = .true.
            rhs = 0.0_dp         ! it held the solution: no out-of-balance force is left
            exit
         end if
         ! predicted spring forces (the linearisation the solve used) ...
         call an%springs%predicted_forces(m%contact%pairs, rvec, ddu, rpred)
         if (fit_scale) fscale = max(maxval(abs(rpred)), 1.0e-300_dp)
         dl = merge(0.0_dp, ddu, an%restrained)
         ! (a hold moves by round-off only: its corrections are measured against the
         ! largest displacement increment of the run so far)
         dnorm = maxval(abs(merge(0.0_dp, ddu, an%restrained)))/ &
                 max(maxval(abs(att%du)), merge(att%duscale, 0.0_dp, hold), tiny(1.0_dp))
         ! (a correction that round-off alone drove is no error of the iterate:
         ! roundoff_share)
         if (.not. slip_reg) dnorm = dnorm*(1.0_dp - rshare)
         ddu = 0.0_dp
         rprev = att%rnorm
         ! ... against the actual ones, after the mode checks
         call update_modes(an, m, st, first, newton, fext_new, fscale, rpred, rvec, rhs, &
                           changed, att, nrest, again, rshare, need_matrix, wasc)
         call line_search(an, m, st, start, first, newton .and. iter > 1 .and. .not. slip_reg, &
                          fscale, rpred, rvec, rhs, changed, att, again, need_matrix, dnorm, &
                          rshare, shortened)
         ! a zero-load increment converging slowly: the bodies placed at rest (rest_start)
         if (newton .and. .not. slip_reg) call rest_start(an, m, st, fext_new, fscale, rpred, &
                                                          rvec, rhs, changed, att, rprev, iter, &
                                                          rest, again, need_matrix, dnorm, wasc)
         if (again) cycle
         if (newton .and. .not. anchored .and. iter >= 2 .and. .not. shortened) then
            call stretch_correction(an, m, st, first, fscale, dl, start%rhs, start%rvec, rpred, &
                                    rvec, rhs, changed, att, dnorm, rshare, again, status)
            if (.not. status%ok()) return
            need_matrix = need_matrix .or. again
            if (again) cycle
         end if
         ! a force at its round-off floor and within 1e-3 TOLR: the next correction would not
         ! count (roundoff_share), so it is not made (where the predictor is used)
         if (newton .and. .not. slip_reg .and. an%pred%enabled .and. rshare >= 1.0_dp .and. &
             att%rnorm <= 1.0e-3_dp*m%contact%opts%tol_residual) dnorm = 0.0_dp
         att%dnorm = dnorm      ! (counts for the Newton return of rough pairs only)
         ! the second pass: the force is balanced, the correction is not (a mode that only
         ! force-free regularising springs hold): the springs elastic from here on
         if (slip_reg .and. .not. anchored .and. att%rnorm <= att%rtol .and. &
             dnorm > m%contact%opts%tol_displacement) then
            call anchor_regularisation(st)
            anchored = .true.
         end if
         ! ideal contact: an early multiplier update (inexact Uzawa, early_update)
         if (att%rnorm > att%rtol .and. .not. anchored .and. &
             early_update(m%contact, st, att%rnorm*fscale)) then
            call augment_multipliers(m%contact, st, done, early=.true.)
            call update_modes(an, m, st, first, newton, fext_new, fscale, rpred, rvec, rhs, &
                              changed, att, nrest, again, rshare, need_matrix, wasc)
            if (again) cycle
         else if (att%rnorm <= att%rtol .and. &
             (.not. newton .or. dnorm <= m%contact%opts%tol_displacement .or. &
              (iter == 1 .and. .not. an%pred%predicted))) then
            ! a pair held below its zero-force point with a tension beyond the limit is off
            ! its law: it opens and the increment goes on (open_held_tension)
            if (rest == 1) then
               call rest_finish(an, m, st, fscale, rpred, rvec, rhs, changed, att, rest, again)
               need_matrix = need_matrix .or. again
               if (again) cycle
            end if
            if (newton .and. .not. anchored) then
               call open_held_tension(m%contact, st, att%rtol*fscale, changed)
               if (any(changed)) then
                  call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
                  att%repeats = att%repeats + 1
                  rshare = 0.0_dp
                  need_matrix = .true.
                  cycle
               end if
            end if
            if (anchored) then
               ! the law's forces: what the anchored springs carried is out-of-balance
               ! force, which must be within the limit
               call release_anchors(st)
               anchored = .false.
               call an%springs%residual_forces(m%contact, st, rpred, rvec, rhs)
               call out_of_balance(an, m%contact%pairs, rhs, rvec, fscale, &
                                   m%contact%opts%tol_residual, att)
               if (att%rnorm > att%rtol) exit
            end if
            ! ideal contact: the bodies balance the forces of the current multipliers; converged
            ! when the penetrations are within tolerance, else an Uzawa update (augment_multipliers)
            done = .not. st%has_ideal
            if (.not. done) call augment_multipliers(m%contact, st, done)
            if (done) then
               att%converged = .true.
               exit
            end if
            call update_modes(an, m, st, first, newton, fext_new, fscale, rpred, rvec, rhs, &
                              changed, att, nrest, again, rshare, need_matrix, wasc)
            if (again) cycle
         end if
         need_matrix = newton .and. .not. an%modified
      end do
      ! a pair frozen by the guard against chatter whose mode fits the solution is no doubt
      if (att%converged .and. an%has_contact) call settle_frozen(m%contact, st, first)
      att%carry = rhs
      att%fscale = fscale
      if (att%converged .and. .not. hold) att%duscale = max(att%duscale, maxval(abs(att%du)))
   end subroutine attempt_pass

   !> Modes and forces of the pairs for the current displacements, and the
   !! out-of-balance force; again: some mode changed, so the increment is
   !! repeated with a new matrix.
   subroutine update_modes(an, m, st, first, newton, fext_new, fscale, rpred, rvec, rhs, changed, &
                           att, nrest, again, rshare, need_matrix, wasc)
      type(analysis_t), intent(in) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: first, newton
      real(dp), intent(in) :: fext_new(:, :), fscale, rpred(:, :)
      real(dp), intent(inout) :: rvec(:, :), rhs(:)
      logical, intent(inout) :: changed(:)
      type(attempt_t), intent(inout) :: att
      integer, intent(inout) :: nrest
      logical, intent(out) :: again
      real(dp), intent(out) :: rshare
      logical, intent(inout) :: need_matrix
      logical, intent(inout) :: wasc(:)        !! (npair) the pairs closed before the evaluation
      wasc = st%md%closed
      call evaluate_pairs(m%contact, st, att%du, changed, first)
      call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
      ! every pair opened at zero load, the forces balanced: at rest on the last (hold_at_rest)
      if (newton .and. any(changed) .and. .not. any(st%md%closed) .and. nrest < 3 .and. &
          att%rnorm <= att%rtol .and. maxval(abs(fext_new)) <= 1.0e-12_dp*an%force_scale) then
         call hold_at_rest(m%contact, st, wasc, changed)
         call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
         nrest = nrest + 1
      end if
      again = att%changing
      ! the share of the out-of-balance force that is round-off, for the next correction
      rshare = 0.0_dp
      if (.not. again) rshare = roundoff_share(att, m%contact%opts%tol_residual)
      if (again) att%repeats = att%repeats + 1
      need_matrix = need_matrix .or. again
   end subroutine update_modes

   !> RETURN, an increment to zero load (no external force, no prescribed
   !! displacement in the deck) whose Newton iteration on the laws converges
   !! only linearly: a solution that changed no mode and left more than a
   !! quarter of the out-of-balance force it started from (a quadratic step
   !! leaves far less), or one after which a pair was frozen by the guard
   !! against chatter, or one that released every pair (then the pairs it
   !! released are the rest's closed pairs: with none closed the system is
   !! singular in the bodies' rigid-body modes; generated scene 49, m2 = 0.25,
   !! the last two pairs released 2.8e-9 above the limit 1.1e-9); every closed
   !! rough pair on its unloading branch.  That
   !! is the approach of the pairs to their zero-force points, where the
   !! branch's tangent vanishes (docs/contact.md, "A stack held only by its
   !! contact"): the pairs on their unloading branches are given their rest
   !! springs (contact_algorithm's start_rest; rest = 1), once an increment.
   !! While every closed pair is a rest pair the system is linear, so a
   !! solution that balances the force is exact: its correction is not tested
   !! against TOLU (dnorm = 0), and the active set (rest_active_set) is updated
   !! after every solution, not only the balanced ones: a change costs one
   !! solution, not two (the newly closed pairs' force-free K_T leave 1e-9 of
   !! the force after the solution that closed them).
   subroutine rest_start(an, m, st, fext_new, fscale, rpred, rvec, rhs, changed, att, rprev, iter, &
                         rest, again, need_matrix, dnorm, wasc)
      type(analysis_t), intent(in) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: fext_new(:, :), fscale, rpred(:, :), rprev
      real(dp), intent(inout) :: rvec(:, :), rhs(:), dnorm
      logical, intent(inout) :: changed(:), again, need_matrix
      type(attempt_t), intent(inout) :: att
      integer, intent(in) :: iter
      integer, intent(inout) :: rest
      logical, intent(in) :: wasc(:)              !! (npair) closed before the last evaluation
      integer :: k, j
      logical :: linear, released
      if (rest == 1 .and. .not. again) then
         linear = .not. st%has_ideal
         do k = 1, size(st%rough)
            j = st%rough(k)
            linear = linear .and. (st%md(j)%rest .or. .not. st%md(j)%closed)
         end do
         if (linear .and. att%rnorm <= att%rtol) dnorm = 0.0_dp
         ! (linear: the active set from every solution, the forces judged beyond what the
         ! solution leaves out of balance; the balanced solution checks it once more)
         if (linear) then
            call rest_active_set(m%contact, st, max(att%rtol, att%rnorm)*fscale, changed)
            if (any(changed)) then
               call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
               att%repeats = att%repeats + 1
               again = .true.
               need_matrix = .true.
            end if
         end if
      end if
      ! (every pair released by the last solution: the rest from the pairs it released)
      released = again .and. .not. any(st%md%closed) .and. any(wasc)
      if (rest /= 0 .or. (again .and. .not. (st%chatter .or. released)) .or. st%has_ideal) return
      if (iter < 2 .and. .not. released) return
      if (.not. (att%rnorm > att%rtol .and. (att%rnorm > 0.25_dp*rprev .or. st%chatter .or. &
                                             released))) return
      if (maxval([0.0_dp, abs(fext_new)]) > 1.0e-12_dp*an%force_scale) return
      if (maxval([0.0_dp, abs(an%ucase)]) > 0.0_dp) return
      do k = 1, size(st%rough)
         j = st%rough(k)
         if (st%md(j)%closed .and. .not. st%md(j)%on_unloading) return
         ! (a steep unloading branch, m2 < 0.5, keeps the law's own iteration unless every pair
         ! was released: its touching band above the point is wide, eps^m2 of the travel, and a
         ! force left on the rest springs there is not one the law can carry near the point;
         ! tests/decks/robust_rest/zero_rest_q8_segment.dat, m2 = 0.38, stalled so)
         if (.not. released .and. m%contact%ifaces(m%contact%pairs(j)%iface)%m2 < 0.5_dp) return
      end do
      if (released) then
         do k = 1, size(st%rough)
            j = st%rough(k)
            if (wasc(j) .and. st%md(j)%on_unloading) st%md(j)%closed = .true.
         end do
      end if
      call start_rest(m%contact, st, changed)
      if (.not. any(changed)) return
      rest = 1
      call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
      att%repeats = att%repeats + 1
      again = .true.
      need_matrix = .true.
   end subroutine rest_start

   !> A balanced solution with the rest springs (rest = 1): the active set
   !! (contact_algorithm's rest_active_set) with the out-of-balance force's
   !! limit; changed, the bodies are solved again (again).  Unchanged, the rest
   !! is found: the laws back (end_rest, rest = 2) and the out-of-balance force
   !! with their forces; where a pair is pressed at zero load, or the laws'
   !! forces leave the bodies out of balance, the Newton iteration on the laws
   !! goes on from there (again).
   subroutine rest_finish(an, m, st, fscale, rpred, rvec, rhs, changed, att, rest, again)
      type(analysis_t), intent(in) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: fscale, rpred(:, :)
      real(dp), intent(inout) :: rvec(:, :), rhs(:)
      logical, intent(inout) :: changed(:)
      type(attempt_t), intent(inout) :: att
      integer, intent(inout) :: rest
      logical, intent(out) :: again
      logical :: ok
      call rest_active_set(m%contact, st, att%rtol*fscale, changed)
      if (any(changed)) then
         call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
         att%repeats = att%repeats + 1
         again = .true.
         return
      end if
      call end_rest(m%contact, st, att%rtol*fscale, ok)
      rest = 2
      call changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
      again = .not. ok .or. att%rnorm > att%rtol
   end subroutine rest_finish

   !> Keep what a Newton solution starts from (line_search).
   subroutine keep_start(att, st, rhs, rvec, start)
      type(attempt_t), intent(in) :: att
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: rhs(:), rvec(:, :)
      type(step_start_t), intent(inout) :: start
      start%du = att%du
      start%rhs = rhs
      start%rvec = rvec
      start%st = st
      start%rnorm = att%rnorm
   end subroutine keep_start

   !> Backtracking line search on the out-of-balance force (Newton, rough pairs):
   !! a solution after which the force grew by more than LS_GROWTH, no pair
   !! changing its mode, is shortened to alpha = 1/2, 1/4, ... (at most
   !! LS_HALVINGS times) of itself until the force is below the one it started
   !! from, or the shortest step; the step of the smallest force is kept, where it is
   !! below the force it started from (else the search failed: the whole solution).  The
   !! bodies are linear, so at alpha the force left is
   !!     r(alpha) = (1 - alpha) r_0 + (f_0 + alpha (f_pred - f_0) - f(alpha)),
   !! r_0 the force the solution was for, f_0 the pairs' forces it started from,
   !! f_pred their linearisation at alpha = 1 and f(alpha) the laws' forces at
   !! the shortened step (evaluate_pairs, from the modes it started from).  A
   !! pair that changes its mode at a shortened step ends the search there (the
   !! matrix is renewed: again).  The contact system scales what it keeps of the
   !! solution (scale_last).
   !!
   !! Why: a steep normal law (p ~ u^(1/m), 1/m = 4 to 7 for the m of measured
   !! surfaces, docs/calibration.md) is nearly flat at a pair just closed and
   !! steep once pressed: Newton's full step from one throws the closure to the
   !! other and back, and the iterates cycle with the force 1e3 times its size
   !! every second solution (a pair at the edge of a bolted joint's contact zone
   !! when the service load is taken off: docs/robustness.md).  The search does
   !! not move a converging iteration: its force does not double.
   subroutine line_search(an, m, st, start, first, active, fscale, rpred, rvec, rhs, changed, &
                          att, again, need_matrix, dnorm, rshare, shortened)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      type(step_start_t), intent(in) :: start
      logical, intent(in) :: first
      logical, intent(in) :: active               !! a later Newton solution of a first pass
      real(dp), intent(in) :: fscale
      real(dp), intent(inout) :: rpred(:, :), rvec(:, :), rhs(:)
      logical, intent(inout) :: changed(:)
      type(attempt_t), intent(inout) :: att
      logical, intent(inout) :: again             !! in: the modes changed (no search)
      logical, intent(inout) :: need_matrix       !! set where a shortened step changes a mode
      real(dp), intent(inout) :: dnorm, rshare    !! the correction, the round-off share
      logical, intent(out) :: shortened           !! the solution was shortened (alpha < 1):
                                                  !! no longer the one stretch_correction takes
      real(dp), allocatable :: step(:, :), fpred(:, :)
      real(dp) :: alpha, best, best_alpha
      integer :: k
      shortened = .false.
      if (.not. active .or. again) return
      if (.not. allocated(start%du) .or. .not. an%sys%scales_last()) return
      if (.not. (att%rnorm > LS_GROWTH*start%rnorm)) return
      step = att%du - start%du
      fpred = rpred
      best = att%rnorm
      best_alpha = 1.0_dp
      alpha = 1.0_dp
      do k = 1, LS_HALVINGS
         alpha = 0.5_dp*alpha
         call evaluate_at(alpha)
         if (again) exit
         if (att%rnorm < best) then
            best = att%rnorm
            best_alpha = alpha
         end if
         if (att%rnorm <= start%rnorm) exit
      end do
      ! no shorter step falls below the force it started from: the search failed, and the
      ! solution stays whole (a creep by the shortest steps would stall the iteration)
      if (.not. (best <= start%rnorm)) best_alpha = 1.0_dp
      if (.not. again .and. alpha /= best_alpha) then
         alpha = best_alpha
         call evaluate_at(alpha)
      end if
      shortened = alpha < 1.0_dp
      if (shortened) then
         call an%sys%scale_last(alpha)
         dnorm = alpha*dnorm
      end if
      if (again) need_matrix = .true.
      if (.not. again) rshare = roundoff_share(att, m%contact%opts%tol_residual)
   contains
      !> The pairs and the out-of-balance force at alpha times the solution.
      subroutine evaluate_at(a)
         real(dp), intent(in) :: a
         st = start%st
         att%du = start%du + a*step
         rpred = start%rvec + a*(fpred - start%rvec)
         call evaluate_pairs(m%contact, st, att%du, changed, first)
         call an%springs%residual_forces(m%contact, st, rpred, rvec, rhs)
         rhs = rhs + (1.0_dp - a)*start%rhs
         call out_of_balance(an, m%contact%pairs, rhs, rvec, fscale, &
                             m%contact%opts%tol_residual, att)
         again = any(changed)
         if (again) then
            att%changing = .true.
            att%nchanged = count(changed)
            att%first_changed = findloc(changed, .true., dim=1)
            att%repeats = att%repeats + 1
         end if
      end subroutine evaluate_at
   end subroutine line_search

   !> The spring forces, the out-of-balance force and the mode changes (flagged
   !! in `changed`) of the attempt after an evaluation of the pairs or a change of
   !! their modes outside one.
   subroutine changed_modes(an, m, st, fscale, rpred, rvec, rhs, changed, att)
      type(analysis_t), intent(in) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      real(dp), intent(in) :: fscale, rpred(:, :)
      real(dp), intent(inout) :: rvec(:, :), rhs(:)
      logical, intent(in) :: changed(:)
      type(attempt_t), intent(inout) :: att
      call an%springs%residual_forces(m%contact, st, rpred, rvec, rhs)
      call out_of_balance(an, m%contact%pairs, rhs, rvec, fscale, m%contact%opts%tol_residual, att)
      att%changing = any(changed)
      att%nchanged = count(changed)
      att%first_changed = findloc(changed, .true., dim=1)
   end subroutine changed_modes

   !> A Newton correction stretched along its own direction where the
   !! out-of-balance force hardly fell (to more than half of the force it was
   !! solved for, the modes kept).  That happens where a mode of the bodies is held
   !! in the matrix by stiffnesses that carry no force: the regularising springs
   !! of pairs slipping at vanishing normal force (K_T^e), the secant of a pair
   !! at rest at zero force.  The solution moves the bodies by the force over
   !! those stiffnesses, and the law's forces, which alone can balance it, change
   !! by their own much smaller stiffness times that move: each solution removes
   !! that small share of the force (a body at zero load with a loaded pair held
   !! by force-free neighbours, generated scenes 66, 104).  Along the direction d
   !! of the correction the out-of-balance force at a multiple a of it is
   !! r(a) = (1 - a) r0 + (predicted spring forces at a) - (the law's forces at
   !! a), r0 the force the correction was solved for: the bodies are linear, and
   !! the interior equations hold for every a.  r(1) is the force now; r is close
   !! to linear in a (r0 + a (r(1) - r0)) as long as the pairs keep their modes
   !! and branches, whatever the stiffnesses were, so the least-squares a of that
   !! line is tried, a = r0.(r0 - r1)/|r0 - r1|^2 (from 2 to 1e12), and kept only
   !! when the out-of-balance force is smaller there (with the modes the law
   !! gives there, which then count as mode changes: again).  A stretch measures
   !! the forces of the law, not the stiffnesses, so it leaves an iteration on the
   !! law; on a convex branch the line lands short of the zero-force point and
   !! the next solution goes on from there.  Quadratic Newton steps (the force
   !! falling below half) are never stretched.  A stretch that is kept is solved
   !! for ((a - 1) r0 with the same matrix: the same move to round-off), so that
   !! the contact system, which recovers the dofs off the contact equations
   !! from the sum of its solutions, has it too; the pairs are evaluated there.
   subroutine stretch_correction(an, m, st, first, fscale, dl, r0, rvb, rpred, rvec, rhs, &
                                 changed, att, dnorm, rshare, again, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      logical, intent(in) :: first
      real(dp), intent(in) :: fscale
      real(dp), intent(in) :: dl(:, :)             !! the last correction (free dofs)
      real(dp), intent(in) :: r0(:)                !! the force it was solved for
      real(dp), intent(in) :: rvb(:, :)            !! the spring forces it started from
      real(dp), intent(in) :: rpred(:, :)          !! the spring forces it predicted
      real(dp), intent(inout) :: rvec(:, :), rhs(:)
      logical, intent(inout) :: changed(:)
      type(attempt_t), intent(inout) :: att
      real(dp), intent(inout) :: dnorm, rshare
      logical, intent(out) :: again
      type(status_t), intent(inout) :: status
      type(contact_state_t) :: st1
      type(attempt_t) :: att1
      real(dp), allocatable :: rvec1(:, :), rhs1(:), dr(:), d2(:, :)
      real(dp) :: a, tol
      again = .false.
      if (size(rhs) == 0 .or. att%rnorm <= att%rtol) return
      if (maxval(abs(rhs)) <= 0.5_dp*maxval(abs(r0))) return
      dr = r0 - rhs
      if (.not. (dot_product(dr, dr) > 0.0_dp)) return
      a = dot_product(r0, dr)/dot_product(dr, dr)
      if (.not. (a >= 2.0_dp)) return
      a = min(a, 1.0e12_dp)
      tol = m%contact%opts%tol_residual
      st1 = st
      att1 = att
      rvec1 = rvec
      rhs1 = rhs
      call try_at(att%du + (a - 1.0_dp)*dl)
      if (att%rnorm < att1%rnorm) then
         ! kept: solved for, and evaluated at that solution
         d2 = 0.0_dp*dl
         rhs = (a - 1.0_dp)*r0
         call an%sys%solve(rhs, d2, status)
         if (.not. status%ok()) then
            call describe_singular(an, status)
            return
         end if
         st = st1
         call try_at(att1%du + merge(0.0_dp, d2, an%restrained))
      end if
      if (.not. (att%rnorm < att1%rnorm)) then
         ! no better there: the correction as it was
         st = st1
         att = att1
         rvec = rvec1
         rhs = rhs1
         changed = .false.
         return
      end if
      dnorm = a*dnorm
      again = any(changed)
      att%changing = again
      att%nchanged = count(changed)
      att%first_changed = findloc(changed, .true., dim=1)
      if (again) att%repeats = att%repeats + 1
      rshare = merge(0.0_dp, roundoff_share(att, tol), again)
   contains
      !> The pairs and the out-of-balance force at the displacement increment du.
      subroutine try_at(du)
         real(dp), intent(in) :: du(:, :)
         att%du = du
         call evaluate_pairs(m%contact, st, att%du, changed, first)
         call an%springs%residual_forces(m%contact, st, rvb + a*(rpred - rvb), rvec, rhs)
         rhs = rhs + (1.0_dp - a)*r0
         call out_of_balance(an, m%contact%pairs, rhs, rvec, fscale, tol, att)
      end subroutine try_at
   end subroutine stretch_correction

   !> The force scale of an attempt's out-of-balance force, settled at its first
   !! solve (rhs: the first right-hand side, carry: the out-of-balance force carried
   !! in): an increment driven only through springs of prescribed nodes (a rigid
   !! body's reference node belongs to no element) has no other force to measure
   !! it against; an increment that holds a zero load (nothing but the carried
   !! out-of-balance force drives it: hold) is measured against the last
   !! increment's scale (the load, a sum of increments, is zero to round-off of
   !! the run's forces); the second attempt of a singular increment to zero load
   !! against the run's forces (zero_load_scale).
   subroutine first_force_scale(an, st, att, rhs, carry, fext_new, slip_reg, fscale, hold, fit)
      type(analysis_t), intent(in) :: an
      type(contact_state_t), intent(in) :: st
      type(attempt_t), intent(in) :: att
      real(dp), intent(in) :: rhs(:), carry(:), fext_new(:, :)
      logical, intent(in) :: slip_reg              !! the second attempt (regularised slip)
      real(dp), intent(inout) :: fscale
      logical, intent(inout) :: hold
      !> nothing loaded but an interference of ideal pairs: the scale is the fit's spring
      !! forces of every solution (attempt_pass), not the penalty's first trial forces
      !! (presses_interference)
      logical, intent(out) :: fit
      fit = fscale <= 1.0e-300_dp .and. presses_interference(st)
      if (fscale <= 1.0e-300_dp .and. an%map%neq > 0) then
         fscale = max(maxval(abs(rhs)), 1.0e-300_dp)
      end if
      if (an%map%neq > 0 .and. maxval(abs(fext_new)) <= 1.0e-12_dp*an%force_scale) then
         hold = maxval(abs(rhs - carry)) <= 1.0e-12_dp*an%force_scale
         if (hold) fscale = max(fscale, att%fscale)
         if (slip_reg) fscale = max(fscale, an%force_scale)
      end if
   end subroutine first_force_scale

   !> 1 when the out-of-balance force of an evaluation is within its round-off
   !! floor (att%rtol less TOLR, module roundoff), else 0.  The next solution's
   !! correction is linear in that force: driven by round-off alone, it is the
   !! response of the bodies to round-off, no error of the iterate.  Where a mode
   !! of the bodies has a stiffness small against the forces that cancel (a body
   !! at rest on one pair at the zero-force end of a convex branch, its chord
   !! stiffness vanishing), that response moves the body by more than TOLU of the
   !! increment after every solution, the force staying at its floor; such a
   !! correction is not held to TOLU (docs/contact.md, "The correction's floor").
   !! A force above its floor (TOLR's part of the limit included) leaves the
   !! correction's test as it is.
   pure real(dp) function roundoff_share(att, tol) result(share)
      type(attempt_t), intent(in) :: att
      real(dp), intent(in) :: tol          !! CONTACT CONVERGE TOLR
      share = 0.0_dp
      if (att%rnorm <= att%rtol - tol) share = 1.0_dp
   end function roundoff_share

   !> Whether the increment starts with an interference of ideal pairs: a closed
   !! ideal pair penetrated beyond the tolerance without a normal multiplier (a
   !! shrink fit pressed in its first increment).  Where nothing else loads such
   !! an increment its only force scale would be the first right-hand side, the
   !! penalty's trial forces eps_n g of the overlap -- 3e3 times the fit's forces
   !! on the hub of docs/contact.md ("An interference fit held by friction"):
   !! balanced to 1e-10 of that, the hub was out of equilibrium by 4.3e-8 of its
   !! largest force, beyond the audit's 1e-8.  Such an increment is measured
   !! against the largest spring force of its last solution instead (the fit's
   !! forces, attempt_pass).
   pure logical function presses_interference(st) result(pressed)
      type(contact_state_t), intent(in) :: st
      integer :: k, j
      pressed = .false.
      if (.not. st%has_ideal .or. .not. allocated(st%ideal)) return
      do k = 1, size(st%ideal)
         j = st%ideal(k)
         if (st%s(j)%closed .and. st%s(j)%un > st%tol_pen .and. st%lam_n(j) <= 0.0_dp) then
            pressed = .true.
            return
         end if
      end do
   end function presses_interference

   !> Put the springs of the current modes into the contact system.
   subroutine set_system(an, m, st, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(in) :: st
      type(status_t), intent(inout) :: status
      call check_finite_springs(st, status)
      if (.not. status%ok()) return
      call an%springs%set_matrices(m%contact, st)
      ! the springs present (a system that keeps a factorization refactorizes when one is lost)
      an%sys%support = merge(1, 0, st%md%kn > 0.0_dp) + merge(2, 0, st%md%kt > 0.0_dp)
      call an%sys%set_springs(an%springs%kstore, status)
      an%system_current = status%ok()
      if (.not. status%ok()) call describe_singular(an, status)
   end subroutine set_system
end module increment_attempt

