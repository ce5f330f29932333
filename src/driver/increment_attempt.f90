!> What one attempt at an increment leaves (nothing committed yet), and the
!! message of an attempt that did not converge: it names the criterion that
!! failed with its value and tolerance, and advises only what is not already
!! in use.
module increment_attempt
   use kinds, only: dp
   use errors, only: status_t, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa
   use contact_types, only: contact_options_t
   use contact_algorithm, only: contact_state_t
   implicit none
   private
   public :: attempt_t, attempt_failure

   !> Outcome of one attempt at an increment (nothing committed yet).
   type :: attempt_t
      real(dp), allocatable :: du(:, :)            !! displacement increment
      real(dp), allocatable :: carry(:)            !! out-of-balance force left, free equations
      integer :: solutions = 0                     !! linear solutions
      integer :: repeats = 0                       !! solutions caused by mode changes
      logical :: converged = .false.
      logical :: changing = .false.                !! springs still changed their modes at the end
      real(dp) :: rnorm = 0.0_dp                   !! relative out-of-balance force
      real(dp) :: fscale = 0.0_dp                  !! the force the out-of-balance force was measured against
      real(dp) :: dnorm = 0.0_dp                   !! last correction relative to the increment (Newton)
      real(dp) :: duscale = 0.0_dp                 !! largest displacement increment of a converged
                                                   !! attempt that was not a hold (the scale of a hold's corrections)
      integer :: nchanged = 0                      !! pairs that changed their mode in the last solution
      integer :: first_changed = 0                 !! the first of them
   end type attempt_t

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
      if (att%converged) return
      advice = '; reduce the increment size'
      if (.not. autoinc) advice = advice//', use OPTIONS AUTOINC'
      advice = advice//' or raise CONTACT REPEATS (now '//itoa(maxrep)//')'
      if (att%changing .or. st%chatter) then
         what = 'the contact states still change ('//itoa(att%nchanged)//' pair(s) in the last solution, '// &
                'the first pair '//itoa(att%first_changed)//')'
         if (st%chatter) what = what//'; a pair changed its state 6 times within the increment (chatter)'
      else if (.not. (returning .or. st%has_ideal)) then
         return
      else if (st%has_ideal .and. att%rnorm <= 1.0e-8_dp .and. st%violation > st%tol_pen) then
         what = 'ideal contact still penetrates or slips by '//rtoa(st%violation)//' > the tolerance '// &
                rtoa(st%tol_pen)//' (AUGMENTED TOL) after '//itoa(st%augmentations)//' multiplier updates'
         advice = advice//' or the AUGMENTED factor'
      else if (att%rnorm > opts%tol_residual) then
         what = 'the relative out-of-balance force '//rtoa(att%rnorm)//' > the tolerance '// &
                rtoa(opts%tol_residual)//' (CONTACT CONVERGE TOLR)'
      else if (returning .and. att%dnorm > opts%tol_displacement) then
         what = 'the last displacement correction '//rtoa(att%dnorm)//' of the increment > the tolerance '// &
                rtoa(opts%tol_displacement)//' (CONTACT CONVERGE TOLU)'
      else
         what = 'ideal contact: slipping pairs still off mu F_n after '//itoa(st%augmentations)// &
                ' multiplier updates'
      end if
      call status%set(STAT_NO_CONVERGENCE, 'no convergence in increment '//itoa(inc)//' after '// &
                      itoa(att%solutions)//' solutions: '//what//advice)
   end subroutine attempt_failure
end module increment_attempt
