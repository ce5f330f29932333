!> Error reporting: the three kinds of errors of the house style.
!!
!! 1. Input errors are collected in an `error_list_t` (code, message,
!!    file:line:col, the offending card echoed with a caret) and printed
!!    together; the program then exits with code 2.
!! 2. Recoverable numerical conditions travel as a `status_t` returned to the
!!    driver, which decides to cut, repeat or stop cleanly.
!! 3. Internal errors stop the program through `assert`, naming file and line,
!!    with exit code 1.
module errors
   use, intrinsic :: iso_c_binding, only: c_int
   use kinds, only: stderr, stdout
   implicit none
   private

   public :: input_error_t, error_list_t, status_t, assert, fatal_internal, terminate, &
         skip_exit_handlers
   public :: printable
   public :: STAT_OK, STAT_SINGULAR, STAT_NEGATIVE_PIVOT, STAT_JACOBIAN, &
             STAT_NO_CONVERGENCE, STAT_CHATTER, STAT_SOLVER, STAT_IO, STAT_INPUT, &
             EXIT_OK, EXIT_INTERNAL, EXIT_INPUT, EXIT_NUMERICAL
   public :: STAT_NONFINITE, EXIT_DOUBTFUL

   !> Status codes for recoverable conditions (kind 2).
   integer, parameter :: STAT_OK = 0
   integer, parameter :: STAT_SINGULAR = 1        !! zero pivot: singular or unrestrained model
   integer, parameter :: STAT_NEGATIVE_PIVOT = 2  !! negative pivot in an SPD system
   integer, parameter :: STAT_JACOBIAN = 3        !! non-positive Jacobian determinant
   integer, parameter :: STAT_NO_CONVERGENCE = 4  !! iterations did not converge
   integer, parameter :: STAT_CHATTER = 5         !! contact states keep switching
   integer, parameter :: STAT_SOLVER = 6          !! other linear-solver failure
   integer, parameter :: STAT_IO = 7              !! result-file failure
   integer, parameter :: STAT_INPUT = 8           !! input rejected
   integer, parameter :: STAT_NONFINITE = 9       !! a NaN or Inf in a solution, force or stress

   !> Process exit codes.
   integer, parameter :: EXIT_OK = 0
   integer, parameter :: EXIT_INTERNAL = 1
   integer, parameter :: EXIT_INPUT = 2
   integer, parameter :: EXIT_NUMERICAL = 3
   integer, parameter :: EXIT_DOUBTFUL = 4        !! completed with doubts (frozen
                                                  !! states, drift, invariants)

   !> Set by skip_exit_handlers: terminate ends the process without the exit handlers.
   logical :: quick_exit = .false.

   !> One input error, located in a file.
   type :: input_error_t
      character(len=:), allocatable :: code     !! short identifier, e.g. E-NUMBER
      character(len=:), allocatable :: message  !! what was expected, what was found
      character(len=:), allocatable :: file
      integer :: line = 0                       !! 1-based line, 0 if not applicable
      integer :: col = 0                        !! 1-based column of the field start
      character(len=:), allocatable :: card     !! the line as read, for the echo
   end type input_error_t

   !> A list of input errors, printed together.
   type :: error_list_t
      type(input_error_t), allocatable :: items(:)
      integer :: n = 0
   contains
      procedure :: add => error_list_add
      procedure :: count => error_list_count
      procedure :: print => error_list_print
      procedure :: clear => error_list_clear
   end type error_list_t

   !> Outcome of a numerical operation.
   type :: status_t
      integer :: code = STAT_OK
      character(len=:), allocatable :: message
   contains
      procedure :: ok => status_ok
      procedure :: set => status_set
   end type status_t

contains

   !> Append one error to the list.
   subroutine error_list_add(this, code, message, file, line, col, card)
      class(error_list_t), intent(inout) :: this
      character(len=*), intent(in) :: code     !! error identifier
      character(len=*), intent(in) :: message  !! full sentence: expected / found
      character(len=*), intent(in), optional :: file
      integer, intent(in), optional :: line, col
      character(len=*), intent(in), optional :: card
      type(input_error_t), allocatable :: tmp(:)
      integer :: cap

      if (.not. allocated(this%items)) allocate (this%items(16))
      cap = size(this%items)
      if (this%n >= cap) then
         allocate (tmp(2*cap))
         tmp(1:this%n) = this%items(1:this%n)
         call move_alloc(tmp, this%items)
      end if
      this%n = this%n + 1
      associate (e => this%items(this%n))
         e%code = code
         e%message = printable(message, 2000)
         e%file = ''
         if (present(file)) e%file = file
         e%line = 0
         if (present(line)) e%line = line
         e%col = 0
         if (present(col)) e%col = col
         e%card = ''
         if (present(card)) e%card = printable(card, max(200, e%col + 20))
      end associate
   end subroutine error_list_add

   !> Text from an input file made safe for a terminal: bytes outside printable
   !! ASCII (binary data, control characters) shown as "?", and at most `limit`
   !! characters, "..." after.
   pure function printable(s, limit) result(r)
      character(len=*), intent(in) :: s
      integer, intent(in) :: limit
      character(len=:), allocatable :: r
      integer :: i, n
      n = min(len(s), limit)
      allocate (character(len=n) :: r)
      do i = 1, n
         if (iachar(s(i:i)) < 32 .or. iachar(s(i:i)) > 126) then
            r(i:i) = '?'
         else
            r(i:i) = s(i:i)
         end if
      end do
      if (len(s) > n) r = r//'...'
   end function printable

   !> Number of errors collected so far.
   pure integer function error_list_count(this) result(n)
      class(error_list_t), intent(in) :: this
      n = this%n
   end function error_list_count

   !> Print every error as `file:line:col: error [CODE]: message`, the card and a caret.
   subroutine error_list_print(this, unit, max_errors)
      class(error_list_t), intent(in) :: this
      integer, intent(in), optional :: unit        !! default: stderr
      integer, intent(in), optional :: max_errors  !! print at most this many (default 50)
      integer :: u, i, nmax, nw
      character(len=16) :: sl, sc
      character(len=:), allocatable :: where

      u = stderr
      if (present(unit)) u = unit
      nmax = 50
      if (present(max_errors)) nmax = max_errors
      do i = 1, min(this%n, nmax)
         associate (e => this%items(i))
            where = e%file
            if (e%line > 0) then
               write (sl, '(i0)') e%line
               where = where//':'//trim(sl)
               if (e%col > 0) then
                  write (sc, '(i0)') e%col
                  where = where//':'//trim(sc)
               end if
            end if
            if (len(where) > 0) where = where//': '
            ! a list of warnings (codes W-...) prints them as such, not as errors
            if (index(e%code, 'W-') == 1) then
               write (u, '(a)') where//'warning ['//e%code//']: '//e%message
            else
               write (u, '(a)') where//'error ['//e%code//']: '//e%message
            end if
            if (len(e%card) > 0) then
               write (u, '(a)') '    | '//e%card
               if (e%col > 0) write (u, '(a)') '    | '//repeat(' ', e%col - 1)//'^'
            end if
         end associate
      end do
      if (this%n > nmax) then
         ! what is left unprinted, named as it is: warnings, errors, or both
         nw = 0
         do i = nmax + 1, this%n
            if (index(this%items(i)%code, 'W-') == 1) nw = nw + 1
         end do
         if (nw == this%n - nmax) then
            write (u, '(a,i0,a)') '... and ', nw, ' more warnings'
         else if (nw == 0) then
            write (u, '(a,i0,a)') '... and ', this%n - nmax, ' more errors'
         else
            write (u, '(a,i0,a,i0,a)') '... and ', this%n - nmax - nw, ' more errors and ', nw, &
               ' more warnings'
         end if
      end if
   end subroutine error_list_print

   !> Forget all errors.
   subroutine error_list_clear(this)
      class(error_list_t), intent(inout) :: this
      this%n = 0
   end subroutine error_list_clear

   !> True when no error condition is set.
   pure logical function status_ok(this)
      class(status_t), intent(in) :: this
      status_ok = this%code == STAT_OK
   end function status_ok

   !> Set a status code with its message.
   pure subroutine status_set(this, code, message)
      class(status_t), intent(inout) :: this
      integer, intent(in) :: code
      character(len=*), intent(in) :: message
      this%code = code
      this%message = message
   end subroutine status_set

   !> Internal consistency check (error kind 3): stops with exit code 1.
   subroutine assert(condition, message, file, line)
      logical, intent(in) :: condition
      character(len=*), intent(in) :: message
      character(len=*), intent(in) :: file   !! source file of the check
      integer, intent(in) :: line            !! source line of the check
      if (.not. condition) call fatal_internal(message, file, line)
   end subroutine assert

   !> End the program with an exit code, quietly (no runtime banner or backtrace).
   !! Fortran units are flushed first; files must already be closed.
   subroutine terminate(code)
      integer, intent(in) :: code
      interface
         subroutine c_exit(status) bind(C, name='exit')
            import :: c_int
            integer(c_int), value :: status
         end subroutine c_exit
         subroutine c_quick_exit(status) bind(C, name='_exit')
            import :: c_int
            integer(c_int), value :: status
         end subroutine c_quick_exit
      end interface
      flush (stdout)
      flush (stderr)
      if (quick_exit) call c_quick_exit(int(code, c_int))
      call c_exit(int(code, c_int))
   end subroutine terminate

   !> Make terminate end the process without running the exit handlers of
   !! the libraries: after HDF5 failed to close a file (it could not flush it
   !! to a full disk) its own clean-up at exit crashes inside the library.
   !! Every file must be closed (or abandoned) before terminate.
   subroutine skip_exit_handlers()
      quick_exit = .true.
   end subroutine skip_exit_handlers

   !> Report an internal error and stop with exit code 1.
   subroutine fatal_internal(message, file, line)
      character(len=*), intent(in) :: message, file
      integer, intent(in) :: line
      write (stderr, '(a,a,i0,a,a)') file, ':', line, ': internal error: ', message
      call terminate(EXIT_INTERNAL)
   end subroutine fatal_internal
end module errors
