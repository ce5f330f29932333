!> Kontakt2D command line: `kontakt2d DECK [options]`.
!!
!! Parses the arguments, reads and defines the model (model_input), runs the
!! driver and maps the outcome to an exit code: 0 success, 1 internal error,
!! 2 input error (deck or command line), 3 numerical failure (finished
!! increments are kept), 4 completed with doubts (frozen contact states, law
!! drift beyond its limit or invariant violations; the increments and pairs
!! are named).
program kontakt2d
   use kinds, only: stdout, stderr
   use errors, only: error_list_t, status_t, terminate, EXIT_OK, EXIT_INPUT, EXIT_NUMERICAL, EXIT_DOUBTFUL, STAT_INPUT
   use strings, only: upper
   use model, only: model_t
   use model_input, only: read_model
   use incremental, only: run_options_t, run_result_t, run_analysis
   use version, only: K2D_VERSION
   use parallel, only: parallel_init
   implicit none

   type(model_t) :: m
   type(error_list_t) :: errs, warns
   type(run_options_t) :: opts
   type(run_result_t) :: res
   type(status_t) :: status
   character(len=:), allocatable :: deck, arg
   integer :: i, nargs

   call parallel_init()     ! MPI runs: rank 0 runs the analysis, the others serve MUMPS (docs/parallel.md)
   opts%results_path = ''
   opts%listing_path = ''
   opts%solver_name = ''
   deck = ''
   nargs = command_argument_count()
   i = 0
   do while (i < nargs)
      i = i + 1
      arg = get_arg(i)
      select case (arg)
      case ('-h', '--help')
         call print_help()
         stop
      case ('-V', '--version')
         write (stdout, '(a)') 'kontakt2d '//K2D_VERSION
         stop
      case ('-o', '--output')
         opts%results_path = option_value(i, arg)
      case ('-l', '--listing')
         opts%listing_path = option_value(i, arg)
      case ('-s', '--solver')
         opts%solver_name = upper(option_value(i, arg))
         if (all(opts%solver_name /= [character(len=7) :: 'SKYLINE', 'UMFPACK', 'DENSE', 'MUMPS'])) then
            call usage_error('--solver expects skyline, umfpack, mumps or dense, found "'//get_arg(i)//'"')
         end if
      case ('-q', '--quiet')
         opts%quiet = .true.
      case default
         if (len(arg) > 0) then
            if (arg(1:1) == '-') call usage_error('unknown option "'//arg//'"')
         end if
         if (len(deck) > 0) call usage_error('only one deck may be given (found "'//deck//'" and "'//arg//'")')
         deck = arg
      end select
   end do
   if (len(deck) == 0) call usage_error('no deck given')

   call read_model(deck, m, errs, warns)
   if (warns%count() > 0) call warns%print()
   if (errs%count() > 0) then
      call errs%print()
      write (stderr, '(a,i0,a)') 'kontakt2d: ', errs%count(), ' error(s) in the input; nothing was computed'
      call terminate(EXIT_INPUT)
   end if

   call run_analysis(m, opts, res, status)
   if (.not. status%ok()) then
      if (.not. res%reported) write (stderr, '(a)') 'kontakt2d: '//status%message
      if (status%code == STAT_INPUT) call terminate(EXIT_INPUT)
      call terminate(EXIT_NUMERICAL)
   end if
   if (res%doubts%steps > 0) call terminate(EXIT_DOUBTFUL)
   call terminate(EXIT_OK)

contains

   function get_arg(k) result(s)
      integer, intent(in) :: k
      character(len=:), allocatable :: s
      integer :: n
      call get_command_argument(k, length=n)
      allocate (character(len=n) :: s)
      if (n > 0) call get_command_argument(k, s)
   end function get_arg

   !> The value following option `name` on the command line.
   function option_value(k, name) result(s)
      integer, intent(inout) :: k
      character(len=*), intent(in) :: name
      character(len=:), allocatable :: s
      if (k >= nargs) call usage_error('option '//name//' expects a value')
      k = k + 1
      s = get_arg(k)
   end function option_value

   subroutine usage_error(msg)
      character(len=*), intent(in) :: msg
      write (stderr, '(a)') 'kontakt2d: '//msg
      write (stderr, '(a)') 'usage: kontakt2d DECK [-o FILE.h5] [-l FILE.lis] [-s SOLVER] [-q]   (--help for details)'
      call terminate(EXIT_INPUT)
   end subroutine usage_error

   subroutine print_help()
      write (stdout, '(a)') 'Kontakt2D '//K2D_VERSION//' - static plane and axisymmetric contact of rough elastic bodies'
      write (stdout, '(a)') ''
      write (stdout, '(a)') 'usage: kontakt2d DECK [options]'
      write (stdout, '(a)') ''
      write (stdout, '(a)') '  DECK                  fixed-format input deck (see docs/deck-format.md)'
      write (stdout, '(a)') '  -o, --output FILE     HDF5 result file (default: <deck name>.h5 in the working directory)'
      write (stdout, '(a)') '  -l, --listing FILE    printed listing (default: results name with .lis; OPTIONS LISTING NONE'
      write (stdout, '(a)') '                        in the deck suppresses it)'
      write (stdout, '(a)') '  -s, --solver NAME     override the deck''s solver: skyline, umfpack, mumps or dense'
      write (stdout, '(a)') '  -q, --quiet           print nothing but errors'
      write (stdout, '(a)') '  -V, --version         print the version and exit'
      write (stdout, '(a)') '  -h, --help            print this help and exit'
      write (stdout, '(a)') ''
      write (stdout, '(a)') 'exit codes: 0 success, 1 internal error, 2 input error (deck or command line),'
      write (stdout, '(a)') '            3 numerical failure (finished increments are kept in the result file),'
      write (stdout, '(a)') '            4 completed with doubts (frozen contact states, law drift, invariant violations:'
      write (stdout, '(a)') '              the increments and pairs are named; result file status "doubtful")'
   end subroutine print_help
end program kontakt2d
