!> The processes of a run: one in the ordinary build, any number under
!! `mpirun` in the MPI build (CMake option KONTAKT2D_MPI, which defines the
!! preprocessor symbol of the same name).
!!
!! The model of an MPI run (docs/parallel.md).  Every process starts the same
!! program on the same deck; rank 0, the root, runs the analysis and writes
!! every output.  The other ranks read the deck and build the model like the
!! root (cheap and replicated), and when the solver layer first needs them
!! they become workers: `serve_commands` keeps them in a loop that receives
!! commands broadcast by the root (`send_command`) and hands each to the
!! solver layer's handler, until the root ends.  So no layer above the
!! solvers ever knows how many processes there are.
!!
!! Only this module and the solver layer see ranks and communicators:
!! `parallel_init` (called once by the main program) starts MPI; ranks other
!! than 0 then have no terminal (their standard output and error units go to
!! the null device), so every message appears once.  MPI is finalized when
!! the process exits, by a C `atexit` handler, so that every exit path of the
!! program (`terminate`, `stop`) ends MPI properly; on the root the handler
!! first releases the workers.
!!
!! In the ordinary build every call is trivial: one process, rank 0, and the
!! communicator handle is 0 (sequential MUMPS ignores it).
!!
!! Ref: MPI Forum, MPI: A Message-Passing Interface Standard, version 3.1
!!      (2015), sec. 5.4 (MPI_Bcast) and sec. 8.7 (MPI_Init, MPI_Finalize).
module parallel
#ifdef KONTAKT2D_MPI
   use mpi
#endif
#ifdef KONTAKT2D_MPI
   use, intrinsic :: iso_c_binding, only: c_int, c_funptr, c_funloc
#endif
   use kinds, only: dp, stdout, stderr
   use errors, only: fatal_internal, terminate, EXIT_OK
   implicit none
   private

   public :: parallel_init, is_root, process_rank, process_count, world_comm, mpi_build
   public :: broadcast, send_command, serve_commands, command_handler_i

   !> First word of the command that ends the workers.
   integer, parameter :: COMMAND_QUIT = -huge(1)
   !> Length of a command (the handler decides what the words mean).
   integer, parameter, public :: COMMAND_WORDS = 4

   logical :: initialized = .false.
   logical :: serving = .false.       ! root: the workers wait in serve_commands
   integer :: my_rank = 0
   integer :: n_ranks = 1

   !> Broadcast from the root to every process.
   interface broadcast
      module procedure broadcast_ints, broadcast_reals, broadcast_int
   end interface broadcast

   abstract interface
      !> What a worker does with one command of the root.
      subroutine command_handler_i(cmd)
         integer, intent(in) :: cmd(:)   !! (COMMAND_WORDS) the command
      end subroutine command_handler_i
   end interface

#ifdef KONTAKT2D_MPI
   interface
      !> C library: run `handler` when the process exits.
      integer(c_int) function c_atexit(handler) bind(C, name='atexit')
         import :: c_int, c_funptr
         type(c_funptr), value :: handler
      end function c_atexit
   end interface
#endif

contains

   !> Start the processes of the run (MPI_Init in the MPI build); call once,
   !! first thing in the main program.  Further calls do nothing.
   subroutine parallel_init()
#ifdef KONTAKT2D_MPI
      logical :: up
      integer :: ierr
      if (initialized) return
      initialized = .true.
      call mpi_initialized(up, ierr)
      if (.not. up) call mpi_init(ierr)
      if (ierr /= MPI_SUCCESS) call fatal_internal('MPI_Init failed', 'parallel.F90', __LINE__)
      call mpi_comm_rank(MPI_COMM_WORLD, my_rank, ierr)
      call mpi_comm_size(MPI_COMM_WORLD, n_ranks, ierr)
      if (c_atexit(c_funloc(finish_at_exit)) /= 0) then
         call fatal_internal('cannot register the MPI finalization at exit', 'parallel.F90', &
                             __LINE__)
      end if
      if (my_rank /= 0) then
         ! a worker has no terminal: every message appears once, from the root
         open (unit=stdout, file='/dev/null', action='write', status='old')
         open (unit=stderr, file='/dev/null', action='write', status='old')
      end if
#else
      initialized = .true.
#endif
   end subroutine parallel_init

   !> Is this process the root (rank 0), the one that writes?
   logical function is_root()
      is_root = my_rank == 0
   end function is_root

   !> Rank of this process (0 in the ordinary build).
   integer function process_rank()
      process_rank = my_rank
   end function process_rank

   !> Number of processes of the run (1 in the ordinary build).
   integer function process_count()
      process_count = n_ranks
   end function process_count

   !> Fortran handle of the communicator of all processes (MPI_COMM_WORLD;
   !! 0 in the ordinary build).
   integer function world_comm()
#ifdef KONTAKT2D_MPI
      world_comm = MPI_COMM_WORLD
#else
      world_comm = 0
#endif
   end function world_comm

   !> Was the program built with MPI?
   logical function mpi_build()
#ifdef KONTAKT2D_MPI
      mpi_build = .true.
#else
      mpi_build = .false.
#endif
   end function mpi_build

   !> Root: broadcast a command to the workers (nothing with one process).
   subroutine send_command(cmd)
      integer, intent(in) :: cmd(COMMAND_WORDS)   !! the command; cmd(1) /= COMMAND_QUIT
      integer :: c(COMMAND_WORDS)
      if (n_ranks == 1) return
      if (my_rank /= 0) call fatal_internal('send_command on a worker', 'parallel.F90', __LINE__)
      if (cmd(1) == COMMAND_QUIT) then
         call fatal_internal('send_command: reserved command', 'parallel.F90', __LINE__)
      end if
      c = cmd
      serving = .true.
      call broadcast_ints(c)
   end subroutine send_command

   !> Worker: receive the root's commands and hand each to `handler`, until
   !! the root ends; then the process exits (code 0: the root's exit code is
   !! the run's).  Never returns.
   subroutine serve_commands(handler)
      procedure(command_handler_i) :: handler   !! what to do with a command
      integer :: cmd(COMMAND_WORDS)
      if (my_rank == 0) call fatal_internal('serve_commands on the root', 'parallel.F90', __LINE__)
      cmd = 0
      do
         call broadcast_ints(cmd)
         if (cmd(1) == COMMAND_QUIT) exit
         call handler(cmd)
      end do
      call terminate(EXIT_OK)
   end subroutine serve_commands

   !> Broadcast an integer array from the root.
   subroutine broadcast_ints(x)
      integer, intent(inout) :: x(:)
#ifdef KONTAKT2D_MPI
      integer :: ierr
      if (n_ranks == 1 .or. size(x) == 0) return
      call mpi_bcast(x, size(x), MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
      if (ierr /= MPI_SUCCESS) call fatal_internal('MPI_Bcast failed', 'parallel.F90', __LINE__)
#else
      associate (unused => x)
      end associate
#endif
   end subroutine broadcast_ints

   !> Broadcast one integer from the root.
   subroutine broadcast_int(x)
      integer, intent(inout) :: x
      integer :: a(1)
      a(1) = x
      call broadcast_ints(a)
      x = a(1)
   end subroutine broadcast_int

   !> Broadcast a real array from the root.
   subroutine broadcast_reals(x)
      real(dp), intent(inout) :: x(:)
#ifdef KONTAKT2D_MPI
      integer :: ierr
      if (n_ranks == 1 .or. size(x) == 0) return
      call mpi_bcast(x, size(x), MPI_DOUBLE_PRECISION, 0, MPI_COMM_WORLD, ierr)
      if (ierr /= MPI_SUCCESS) call fatal_internal('MPI_Bcast failed', 'parallel.F90', __LINE__)
#else
      associate (unused => x)
      end associate
#endif
   end subroutine broadcast_reals

#ifdef KONTAKT2D_MPI
   !> At process exit: release the workers (root), then finalize MPI.
   subroutine finish_at_exit() bind(C)
      logical :: done
      integer :: ierr, c(COMMAND_WORDS)
      call mpi_finalized(done, ierr)
      if (done) return
      if (my_rank == 0 .and. serving) then
         c = 0
         c(1) = COMMAND_QUIT
         call mpi_bcast(c, COMMAND_WORDS, MPI_INTEGER, 0, MPI_COMM_WORLD, ierr)
      end if
      call mpi_finalize(ierr)
   end subroutine finish_at_exit
#endif
end module parallel
