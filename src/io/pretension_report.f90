!> The pretension sections in the listing and on the terminal: the force
!! across each section and its shortening after a step, and the sections'
!! definition in the header.
module pretension_report
   use kinds, only: dp
   use strings, only: itoa
   use model, only: model_t
   use records, only: step_record_t
   implicit none
   private
   public :: list_pretension_sections, list_pretension_step, list_pretension_summary

contains

   !> One line per section: its name, nodes, axis, preload and mode.
   subroutine list_pretension_sections(u, m)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer :: k
      character(len=200) :: line
      if (.not. allocated(m%pretensions)) return
      do k = 1, size(m%pretensions)
         associate (p => m%pretensions(k))
            write (line, '(a,i0,a,a1,a,es12.5,a,i0,a,i0)') ' Pretension   : "'//p%name//'", ', &
                  size(p%nodes), &
               ' nodes across ', merge('x', 'y', p%axis == 1), ', preload ', p%force, &
               ' x factor of case ', &
               p%icase, ', reference node ', p%ref
            write (u, '(a)') trim(line)//merge(' (held: locked)', ' (held: force) ', p%mode == 1)
         end associate
      end do
   end subroutine list_pretension_sections

   !> The force across each section (from the elements at the cut) and its
   !! shortening after the step.
   subroutine list_pretension_step(u, m, srec)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(step_record_t), intent(in) :: srec
      integer :: k
      if (.not. allocated(srec%pretension_force)) return
      do k = 1, size(srec%pretension_force)
         write (u, '(a,i0,a,es17.10,a,es14.7)') ' pretension   increment ', srec%step, &
               ' section "'// &
            m%pretensions(k)%name//'": force ', srec%pretension_force(k), ', shortening ', &
            srec%pretension_shortening(k)
      end do
   end subroutine list_pretension_step

   !> The summary's lines: every section's force and shortening at the last
   !! step whose body fields were computed (nothing without sections).
   subroutine list_pretension_summary(u, m, srec)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      type(step_record_t), intent(in) :: srec
      integer :: k
      if (.not. allocated(srec%pretension_force)) return
      do k = 1, size(srec%pretension_force)
         write (u, '(a,i0,a,es17.10,a,es14.7)') ' pretension section "'//m%pretensions(k)%name// &
               '" at increment ', &
            srec%step, ': force ', srec%pretension_force(k), ', shortening ', &
            srec%pretension_shortening(k)
      end do
   end subroutine list_pretension_summary
end module pretension_report
