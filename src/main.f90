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
   use errors, only: error_list_t, status_t, terminate, EXIT_OK, EXIT_INPUT, EXIT_NUMERICAL, &
         EXIT_DOUBTFUL, STAT_INPUT
   use, intrinsic :: iso_c_binding, only: c_char, c_null_char, c_ptr, c_associated
   use strings, only: upper, basename, strip_extension
   use model, only: model_t
   use run_plan, only: solver_code, SOLVER_UNSET
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

   call parallel_init()     ! MPI runs: rank 0 runs the analysis, the
                            ! others serve MUMPS (docs/parallel.md)
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
         if (solver_code(opts%solver_name) == SOLVER_UNSET) then
            call usage_error('--solver expects skyline, umfpack, mumps or dense, found "'// &
                             get_arg(i)//'"')
         end if
      case ('-q', '--quiet')
         opts%quiet = .true.
      case default
         if (len(arg) > 0) then
            if (arg(1:1) == '-') call usage_error('unknown option "'//arg//'"')
         end if
         if (len(deck) > 0) then
            call usage_error('only one deck may be given (found "'//deck//'" and "'//arg//'")')
         end if
         deck = arg
      end select
   end do
   if (len(deck) == 0) call usage_error('no deck given')

   call read_model(deck, m, errs, warns)
   if (warns%count() > 0) call warns%print()
   if (errs%count() > 0) then
      call errs%print()
      write (stderr, '(a,i0,a)') 'kontakt2d: ', errs%count(), &
            ' error(s) in the input; nothing was computed'
      call terminate(EXIT_INPUT)
   end if

   call check_output_paths(deck, m, opts)

   call run_analysis(m, opts, res, status)
   if (.not. status%ok()) then
      if (.not. res%reported) write (stderr, '(a)') 'kontakt2d: '//status%message
      if (status%code == STAT_INPUT) call terminate(EXIT_INPUT)
      call terminate(EXIT_NUMERICAL)
   end if
   if (res%doubts%steps > 0) call terminate(EXIT_DOUBTFUL)
   call terminate(EXIT_OK)

contains

   !> The result file and the listing (as given, or their defaults: the deck's
   !! name with .h5, the result file's with .lis) must not be an input file
   !! (the deck, its .msh): writing them would destroy it.  A command-line
   !! error (exit 2) before anything is written.
   subroutine check_output_paths(deck, m, opts)
      character(len=*), intent(in) :: deck
      type(model_t), intent(in) :: m
      type(run_options_t), intent(in) :: opts
      character(len=:), allocatable :: res_path, lis_path
      res_path = opts%results_path
      if (len(res_path) == 0) res_path = strip_extension(basename(deck))//'.h5'
      lis_path = opts%listing_path
      if (len(lis_path) == 0) lis_path = strip_extension(res_path)//'.lis'
      call refuse_input(deck, m, 'result file', res_path, '-o')
      if (m%listing_level /= 'NONE') call refuse_input(deck, m, 'listing', lis_path, '-l')
   end subroutine check_output_paths

   !> An output path that is the deck or its mesh file: a command-line error.
   subroutine refuse_input(deck, m, what, out, option)
      character(len=*), intent(in) :: deck
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: what, out, option
      if (same_file(out, deck)) call usage_error('the '//what//' "'//out// &
                                                 '" is the input deck: '// &
                                                 'give another path with '//option)
      if (allocated(m%mesh_file)) then
         if (same_file(out, m%mesh_file)) call usage_error('the '//what//' "'//out// &
                                                           '" is the mesh file '// &
                                                           'of the deck: give another path &
                                                           &with '//option)
      end if
   end subroutine refuse_input

   !> Whether two paths name the same existing file (realpath(3) of both).
   logical function same_file(a, b)
      character(len=*), intent(in) :: a, b
      character(len=:), allocatable :: ra, rb
      same_file = .false.
      ra = real_path(a)
      if (len(ra) == 0) return
      rb = real_path(b)
      same_file = ra == rb
   end function same_file

   !> The canonical absolute path of an existing file, '' if there is none.
   function real_path(path) result(r)
      character(len=*), intent(in) :: path
      character(len=:), allocatable :: r
      interface
         function c_realpath(p, resolved) bind(C, name='realpath') result(q)
            import :: c_char, c_ptr
            character(kind=c_char), intent(in) :: p(*)
            character(kind=c_char), intent(out) :: resolved(*)
            type(c_ptr) :: q
         end function c_realpath
      end interface
      character(kind=c_char) :: buf(4097)
      integer :: n
      buf = c_null_char
      if (.not. c_associated(c_realpath(path//c_null_char, buf))) then
         r = ''
         return
      end if
      n = 0
      do while (n < size(buf) - 1)
         if (buf(n + 1) == c_null_char) exit
         n = n + 1
      end do
      allocate (character(len=n) :: r)
      r = transfer(buf(1:n), r)
   end function real_path

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
      write (stderr, '(a)') &
            'usage: kontakt2d DECK [-o FILE.h5] [-l FILE.lis] [-s SOLVER] [-q]   (--help for &
            &details)'
      call terminate(EXIT_INPUT)
   end subroutine usage_error

   subroutine print_help()
      write (stdout, '(a)') 'Kontakt2D '//K2D_VERSION// &
            ' - static plane and axisymmetric contact of rough elastic bodies'
      write (stdout, '(a)') ''
      write (stdout, '(a)') 'usage: kontakt2d DECK [options]'
      write (stdout, '(a)') ''
      write (stdout, '(a)') &
            '  DECK                  fixed-format input deck (see docs/deck-format.md)'
      write (stdout, '(a)') &
            '  -o, --output FILE     HDF5 result file (default: <deck name>.h5 in the working &
            &directory)'
      write (stdout, '(a)') &
            '  -l, --listing FILE    printed listing (default: results name with .lis; OPTIONS &
            &LISTING NONE'
      write (stdout, '(a)') '                        in the deck suppresses it)'
      write (stdout, '(a)') &
            '  -s, --solver NAME     override the deck''s solver: skyline, umfpack, mumps or dense'
      write (stdout, '(a)') '  -q, --quiet           print nothing but errors'
      write (stdout, '(a)') '  -V, --version         print the version and exit'
      write (stdout, '(a)') '  -h, --help            print this help and exit'
      write (stdout, '(a)') ''
      write (stdout, '(a)') &
            'exit codes: 0 success, 1 internal error, 2 input error (deck or command line),'
      write (stdout, '(a)') &
            '            3 numerical failure (finished increments are kept in the result file),'
      write (stdout, '(a)') &
            '            4 completed with doubts (frozen contact states, law drift, invariant &
            &violations:'
      write (stdout, '(a)') &
            '              the increments and pairs are named; result file status "doubtful")'
   end subroutine print_help
end program kontakt2d
