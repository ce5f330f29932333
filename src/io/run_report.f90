!> One run report: every output of a run -- the result file, the listing and
!! the terminal -- with their default paths, written from the records of the
!! run (run information, step record, body and contact fields, the summary).
!! The driver talks to this module only; it holds no unit, path or HDF5 file.
!!
!! Life cycle (the driver's calls):
!!
!!     call rep%start(deck_file, results_path, listing_path, level, quiet)
!!                                    ! default paths: <deck>.h5, <results>.lis; the clock
!!     call rep%open(m, numbering, info, body, set_up_failed, status)
!!                                    ! the listing's header (method, numbering, sections,
!!                                    ! FULL: the input), the result file (mesh, run
!!                                    ! information, contact definition), the terminal's header
!!     do accepted step
!!        call rep%note_reversals(c, pa_old, pa, srec, nwarn)   ! warnings of the step
!!        call rep%write_step(m, srec, body, fields, status)    ! result file, listing, progress
!!     end do                         ! (rep%note_cut: a step cut by automatic increments)
!!     call rep%finish(m, body, fields, fin, status)
!!                                    ! doubts or failure, the summary (listing, terminal and
!!                                    ! the result file's /summary), /cycles, the status, close
!!
!! Outputs and what each gets:
!!  - result file (results_hdf5): mesh, run information, every written step, /cycles,
!!    /summary (everything the listing's closing summary says), the status;
!!  - listing (listing, run_summary, pretension_report): header, the steps (FULL: every
!!    one; SHORT: the last), warnings, doubts or failure, summary, dissipation, sections;
!!  - terminal: header and one progress line a step (stdout), the closing lines
!!    (completed on stdout; doubts and failures on stderr), summary (stdout).
!!
!! Failures: a listing that cannot be opened, or a result file that cannot be
!! created, is a command-line error (STAT_INPUT) and leaves neither file; a
!! result file created but not written (a full disk) is an output failure.
!! A run that failed at set-up (open with set_up_failed) keeps the mesh and the
!! status in the result file, and the failure in the listing, without a summary.
module run_report
   use kinds, only: dp, i8, stdout, stderr
   use errors, only: status_t, STAT_INPUT, STAT_IO
   use strings, only: itoa, strip_extension, basename
   use model, only: model_t
   use contact_types, only: contact_def_t
   use records, only: step_record_t, body_fields_t, contact_fields_t, run_info_t, run_doubts_t, &
                      cycle_table_t, numbering_report_t
   use results_hdf5, only: results_file_t
   use run_summary, only: run_summary_t, summarise_run, write_run_summary, write_dissipation, &
                          stage_case, &
                          estimate_peak_t, note_estimate_peak
   use pretension_report, only: list_pretension_sections, list_pretension_step, &
                                list_pretension_summary
   use listing, only: list_header, list_method, list_input, list_step, list_progress_header, &
                      list_progress, list_completed, list_failed, list_doubts, close_listing, &
                      list_reversals, list_numbering
   implicit none
   private
   public :: run_report_t, run_end_t

   !> What the end of a run reports besides its last fields: the records the
   !! driver kept over the steps.
   type :: run_end_t
      integer :: completed = 0                      !! steps finished
      integer, allocatable :: solutions(:)          !! solutions of every accepted step
      real(dp), allocatable :: drift(:)             !! law drift of every accepted step
      real(dp), allocatable :: ua(:), pa(:)         !! (npair) reversal points A of the pairs
      type(run_doubts_t) :: doubts                  !! the doubtful steps
      character(len=:), allocatable :: doubt_line   !! their one-line summary (step_audit)
      type(cycle_table_t) :: cycles                 !! the load cycles of the history
      type(run_info_t) :: info                      !! what the run used (the advice to doubts)
      integer :: warnings = 0                       !! warnings printed about the method
   end type run_end_t

   !> The outputs of one run.
   type :: run_report_t
      private
      type(results_file_t) :: rf
      character(len=:), allocatable :: rpath        !! result file
      character(len=:), allocatable :: lis_path     !! listing file
      character(len=:), allocatable :: lis_level    !! FULL, SHORT or NONE
      integer :: lu = 0                             !! listing unit
      logical :: have_lis = .false.                 !! the listing is open
      logical :: quiet = .false.                    !! no terminal output except errors
      logical :: set_up_failed = .false.            !! the run stopped before its first increment
      integer(i8) :: t0 = 0, rate = 1               !! clock at the start of the run
      type(step_record_t) :: pret_last              !! the last step with section forces (summary)
      type(estimate_peak_t) :: est_peak             !! the estimate at the largest strain energy
      integer :: icase = 1                          !! the load case of the progress lines
   contains
      procedure :: start => report_start
      procedure :: open => report_open
      procedure :: results_path => report_results_path
      procedure :: lists_every_step => report_lists_every_step
      procedure :: note_cut => report_note_cut
      procedure :: note_reversals => report_note_reversals
      procedure :: write_step => report_write_step
      procedure :: finish => report_finish
   end type run_report_t

contains

   !> The paths of the outputs and the clock of the run.  results_path '' (or
   !! absent): <deck name>.h5 in the working directory; listing_path '' (or
   !! absent): the result path with .lis.
   subroutine report_start(this, deck_file, level, quiet, results_path, listing_path)
      class(run_report_t), intent(inout) :: this
      character(len=*), intent(in) :: deck_file      !! the deck (its name gives the default)
      character(len=*), intent(in) :: level          !! OPTIONS LISTING: FULL, SHORT or NONE
      logical, intent(in) :: quiet                   !! -q: nothing on the terminal but errors
      character(len=*), intent(in), optional :: results_path, listing_path   !! -o, -l
      call system_clock(this%t0, this%rate)
      this%rpath = strip_extension(basename(deck_file))//'.h5'
      if (present(results_path)) then
         if (len(results_path) > 0) this%rpath = results_path
      end if
      this%lis_path = strip_extension(this%rpath)//'.lis'
      if (present(listing_path)) then
         if (len(listing_path) > 0) this%lis_path = listing_path
      end if
      this%lis_level = level
      this%quiet = quiet
   end subroutine report_start

   !> The result file's path.
   function report_results_path(this) result(path)
      class(run_report_t), intent(in) :: this
      character(len=:), allocatable :: path
      path = this%rpath
   end function report_results_path

   !> Does the listing print every step (FULL)?  Then every step needs its
   !! body fields.
   pure logical function report_lists_every_step(this) result(yes)
      class(run_report_t), intent(in) :: this
      yes = this%have_lis .and. this%lis_level == 'FULL'
   end function report_lists_every_step

   !> The listing, then the result file (nothing is left behind if either
   !! fails), then the terminal's header.
   subroutine report_open(this, m, numbering, info, body, set_up_failed, status)
      class(run_report_t), intent(inout) :: this
      type(model_t), intent(in) :: m
      type(numbering_report_t), intent(in) :: numbering   !! what the equation numbering did
      type(run_info_t), intent(in) :: info                !! what the run uses
      type(body_fields_t), intent(in) :: body             !! the Gauss-point layout
      logical, intent(in) :: set_up_failed                !! stopped before its first increment
      type(status_t), intent(inout) :: status
      integer :: ios
      character(len=256) :: iomsg

      this%set_up_failed = set_up_failed
      this%have_lis = this%lis_level /= 'NONE'
      if (this%have_lis) then
         open (newunit=this%lu, file=this%lis_path, status='replace', action='write', &
               access='stream', form='formatted', iostat=ios, iomsg=iomsg)
         if (ios /= 0) then
            call status%set(STAT_INPUT, 'cannot open the listing file '//this%lis_path//': '// &
                            trim(iomsg))
            this%have_lis = .false.
            return
         end if
         call list_header(this%lu, m, info)
         call list_numbering(this%lu, numbering)
         call list_method(this%lu, info)
         call list_pretension_sections(this%lu, m)
         if (this%lis_level == 'FULL') call list_input(this%lu, m)
      end if
      call this%rf%create(this%rpath, m, body, status)
      if (status%ok()) call this%rf%write_run_info(info, status)
      if (info%npair > 0 .and. status%ok()) then
         call this%rf%write_contact_definition(m%contact, info, status)
      end if
      if (status%ok()) call this%rf%write_header(m, info, numbering, status)
      if (.not. status%ok()) then
         ! a result path that cannot be created is a command-line error; a file created
         ! but not written (a full disk) is an output failure (exit 3)
         if (.not. this%rf%is_open()) status%code = STAT_INPUT
         call this%rf%close()
         if (this%have_lis) close (this%lu, status='delete')
         this%have_lis = .false.
         return
      end if
      this%icase = stage_case(m)
      if (.not. this%quiet) then
         call list_header(stdout, m, info)
         call list_numbering(stdout, numbering)
         call list_method(stdout, info)
         call list_pretension_sections(stdout, m)
         write (stdout, '(a)') ' Results      : '//this%rpath
         if (this%have_lis) write (stdout, '(a)') ' Listing      : '//this%lis_path
         write (stdout, '(a)') repeat('-', 78)
         if (m%ncase > 1) write (stdout, '(a,i0,a,i0,a)') ' Load factor  : of case ', &
            this%icase, ' (of ', m%ncase, ' cases) in the progress lines: its factor varies most'
         call list_progress_header(stdout, info%npair > 0)
      end if
   end subroutine report_open

   !> A step cut by the automatic increments: one terminal line.
   subroutine report_note_cut(this, inc, fraction)
      class(run_report_t), intent(in) :: this
      integer, intent(in) :: inc                     !! deck increment
      real(dp), intent(in) :: fraction               !! the new step, fraction of the deck increment
      if (.not. this%quiet) write (stdout, '(a,i0,a,f9.6)') '      cut: deck increment ', inc, &
         ', step fraction ', fraction
   end subroutine report_note_cut

   !> The pairs of a step that took a reversal point beyond the admissible
   !! range of their unloading law: warned on the terminal and in the
   !! listing, kept in the step record (listing's list_reversals).
   subroutine report_note_reversals(this, c, pa_old, pa, srec, nwarn)
      class(run_report_t), intent(in) :: this
      type(contact_def_t), intent(in) :: c
      real(dp), intent(in) :: pa_old(:), pa(:)       !! (npair) reversal pressures before and after
      type(step_record_t), intent(inout) :: srec     !! the step (its warnings set)
      integer, intent(inout) :: nwarn                !! warnings of the run
      call list_reversals(c, pa_old, pa, srec, this%lu, this%have_lis, nwarn)
   end subroutine report_note_reversals

   !> An accepted step: the result file (a written step), the listing (FULL:
   !! every step; SHORT: the last) and the terminal's progress line.
   subroutine report_write_step(this, m, srec, body, fields, status)
      class(run_report_t), intent(inout) :: this
      type(model_t), intent(in) :: m
      type(step_record_t), intent(in) :: srec
      type(body_fields_t), intent(in) :: body
      type(contact_fields_t), intent(in) :: fields   !! (unallocated without contact)
      type(status_t), intent(inout) :: status
      integer(i8) :: t1
      logical :: listed
      if (srec%written) call this%rf%write_increment(srec, body, status, fields)
      listed = this%have_lis .and. (this%lis_level == 'FULL' .or. srec%last)
      if (listed .and. status%ok()) then
         call list_step(this%lu, m, srec, body, fields, this%lis_path, status, &
                        this%lis_level /= 'FULL')
      end if
      if (listed .and. status%ok()) call list_pretension_step(this%lu, m, srec)
      if (allocated(srec%pretension_force)) this%pret_last = srec
      if (srec%full) call note_estimate_peak(this%est_peak, srec%step, body, fields)
      if (.not. status%ok()) return
      call system_clock(t1)
      if (.not. this%quiet) then
         call list_progress(stdout, srec, body, real(t1 - this%t0, dp)/real(this%rate, dp), &
                            this%icase, fields)
         flush (stdout)
      end if
   end subroutine report_write_step

   !> The end of the run: the listing's closing lines (doubts or failure),
   !! the summary in the listing, the result file (/cycles, /summary) and on
   !! the terminal, the result file's status, the files closed.  reported:
   !! a failure was printed (on the error unit).
   subroutine report_finish(this, m, body, fields, fin, status, reported)
      class(run_report_t), intent(inout) :: this
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body        !! body fields of the last step
      type(contact_fields_t), intent(in) :: fields   !! contact fields of the last step
      type(run_end_t), intent(in) :: fin
      type(status_t), intent(inout) :: status   !! a failure to write an output ends it
      logical, intent(out) :: reported
      type(run_summary_t) :: s
      type(status_t) :: st
      integer :: done, every
      logical :: ran                            !! every increment done (what fails now, fails
                                                !! after them)
      reported = .false.
      ran = status%ok() .and. .not. this%set_up_failed
      done = merge(-1, fin%completed, this%set_up_failed)
      every = merge(1, m%results_every, this%set_up_failed)
      if (.not. this%set_up_failed) call summarise(this, m, body, fields, fin, s)
      ! the listing's closing lines and summary; the listing is then closed and
      ! checked (a full disk shows only at its close)
      if (this%have_lis) then
         if (status%ok() .and. fin%doubts%steps > 0) then
            call list_doubts(this%lu, fin%doubts, fin%doubt_line, '', fin%info)
         else if (.not. status%ok()) then
            call list_failed(this%lu, done, status%message, this%rpath, every)
         end if
         if (.not. this%set_up_failed) then
            call write_run_summary(this%lu, s, s%seconds)
            if (allocated(fields%dissipated_energy)) then
               call write_dissipation(this%lu, m, fields, fin%cycles)
            end if
            call list_pretension_summary(this%lu, m, this%pret_last)
         end if
         call close_listing(this%lu, this%lis_path, status)
      end if
      if (status%ok() .and. fin%cycles%ncycle > 0) call this%rf%write_cycles(fin%cycles, status)
      ! the summary in the result file: also after a numerical failure (its own failure then
      ! is not the run's); not after an output failure (HDF5 does not recover from one)
      if (.not. this%set_up_failed) then
         if (status%ok()) then
            call this%rf%write_summary(s, status)
         else if (status%code /= STAT_IO) then
            call this%rf%write_summary(s, st)
         end if
      end if
      if (status%ok() .and. fin%doubts%steps > 0) then
         ! completed, but not to be trusted without a look: exit code 4
         call this%rf%set_status('doubtful: '//fin%doubt_line, status)
         if (status%ok()) call list_doubts(stderr, fin%doubts, fin%doubt_line, this%rpath)
      else if (status%ok()) then
         call this%rf%set_status('completed', status)
         if (status%ok() .and. .not. this%quiet) then
            call list_completed(stdout, fin%completed, this%rpath)
         end if
      end if
      if (.not. status%ok()) then
         if (this%set_up_failed) then
            call this%rf%set_status('failed at set-up: '//status%message)
         else if (ran) then
            call this%rf%set_status('failed after the last increment ('//itoa(fin%completed)// &
                                    '): '//status%message)
         else
            call this%rf%set_status('failed at increment '//itoa(fin%completed + 1)//': '// &
                                    status%message)
         end if
         reported = .true.
         call list_failed(stderr, done, status%message, this%rpath, every)
      end if
      if (.not. (this%set_up_failed .or. this%quiet)) then
         call write_run_summary(stdout, s, s%seconds)
         if (allocated(fields%dissipated_energy)) then
            call write_dissipation(stdout, m, fields, fin%cycles)
         end if
         call list_pretension_summary(stdout, m, this%pret_last)
      end if
      call this%rf%close(status)
   end subroutine report_finish

   !> The figures of the closing summary, once for the listing, the terminal
   !! and the result file: run_summary's, with the time, the doubts, the
   !! warnings and the pretension sections of the run.
   subroutine summarise(this, m, body, fields, fin, s)
      class(run_report_t), intent(in) :: this
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      type(contact_fields_t), intent(in) :: fields
      type(run_end_t), intent(in) :: fin
      type(run_summary_t), intent(out) :: s
      integer(i8) :: t1
      call summarise_run(m, body, fields, fin%solutions, fin%drift, fin%ua, fin%pa, s, &
                         this%est_peak)
      call system_clock(t1)
      s%seconds = real(t1 - this%t0, dp)/real(max(this%rate, 1_i8), dp)
      s%warnings = fin%warnings
      s%doubtful = fin%doubts%steps
      s%doubt_frozen = fin%doubts%frozen
      s%doubt_drift = fin%doubts%drift
      s%doubt_violations = fin%doubts%violations
      s%first_doubtful = fin%doubts%first
      s%doubts = ''
      if (fin%doubts%steps > 0 .and. allocated(fin%doubt_line)) s%doubts = fin%doubt_line
      s%doubt_details = ''
      if (allocated(fin%doubts%details)) s%doubt_details = fin%doubts%details
      if (allocated(this%pret_last%pretension_force)) then
         s%pretension_step = this%pret_last%step
         s%pretension_force = this%pret_last%pretension_force
         s%pretension_shortening = this%pret_last%pretension_shortening
      end if
   end subroutine summarise
end module run_report
