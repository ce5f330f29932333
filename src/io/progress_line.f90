!> The terminal's progress line of a step whose body fields were not computed.
!!
!! A contact run skips the full displacement field, the stresses, the
!! reactions and the equilibrium check of the steps it neither writes
!! (OPTIONS RESULTS) nor lists (step_record_t%full = .false.); their
!! contact solution is exact.  Their progress line shows the contact-side
!! figures (closed and slipping pairs, solutions, repeats, residual) and a
!! dash for max |u|, which is not known for them; every other step gets
!! listing's progress line.
module progress_line
   use kinds, only: dp
   use records, only: step_record_t, body_fields_t, contact_fields_t, NS_OPEN, TS_SLIP
   use listing, only: list_progress
   implicit none
   private
   public :: list_step_progress

contains

   !> One progress line for the terminal (columns of list_progress_header).
   subroutine list_step_progress(u, step, body, seconds, contact)
      integer, intent(in) :: u
      type(step_record_t), intent(in) :: step
      type(body_fields_t), intent(in) :: body
      real(dp), intent(in) :: seconds                           !! elapsed since the start of the run
      type(contact_fields_t), intent(in), optional :: contact   !! used when step%contact
      if (step%full .or. .not. (step%contact .and. present(contact))) then
         call list_progress(u, step, body, seconds, contact)
         return
      end if
      write (u, '(i6, f13.5, a12, i8, i6, i8, i4, es11.3, f12.3)') step%step, maxval(abs(step%lambda)), &
         '-', count(contact%normal_state /= NS_OPEN), &
         count(contact%normal_state /= NS_OPEN .and. contact%tangential_state == TS_SLIP), step%solutions, &
         step%repeats, step%residual, seconds
   end subroutine list_step_progress
end module progress_line
