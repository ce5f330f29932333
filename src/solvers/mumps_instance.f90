!> One MUMPS instance (double precision, `DMUMPS`) through MUMPS's native
!! Fortran interface, the same in the sequential and the MPI build.
!!
!! What every user of MUMPS in Kontakt2D shares: the structure `DMUMPS_STRUC`
!! of MUMPS's `dmumps_struc.h` (held through a pointer, so that the solver
!! object that owns it may be moved without MUMPS noticing), the life cycle
!! (JOB = -1 start, 1 analysis, 2 factorization, 3 solve, -2 end), silence
!! on the terminal (ICNTL(1:4)), and the meaning of MUMPS's error codes.
!!
!! MPI.  MUMPS's calls are collective over the communicator of all processes
!! (the matrix and the right-hand side are centralized on the host, rank 0:
!! ICNTL(18) = 0, PAR = 1).  Only the root runs the program past its first
!! MUMPS instance: the other ranks become workers when they reach `start`
!! (`parallel%serve_commands` never returns) and mirror each call of the
!! root: `run` broadcasts (job, instance key, SYM) and the control arrays
!! ICNTL and CNTL before calling DMUMPS, and the worker makes the same call on
!! its own instance with the same key.  The global information INFOG is the
!! same on every process after each call, and what MUMPS returns on the host
!! (solution, null-pivot list, Schur complement) is on the root, which needs
!! it.  With one process `run` is a plain call.
!!
!! Ref: MUMPS 5.5 Users' guide (Amestoy, Buttari, Duff, Guermouche,
!!      L'Excellent, Ucar, 2022): sec. 5.1 (JOB), 5.2-5.4 (COMM, PAR, SYM,
!!      centralized assembled input), 6 (ICNTL, CNTL), 7 (INFO, INFOG),
!!      8 (error and warning diagnostics).
module mumps_instance
   use kinds, only: i8
   use errors, only: fatal_internal
   use strings, only: itoa
   use parallel, only: parallel_init, is_root, process_count, world_comm, broadcast, send_command, &
                       serve_commands, COMMAND_WORDS
   implicit none
   private

   include 'dmumps_struc.h'

   public :: mumps_instance_t, mumps_error_text, mumps_size
   public :: JOB_START, JOB_END, JOB_ANALYSE, JOB_FACTORIZE, JOB_SOLVE

   !> MUMPS's JOB values.
   integer, parameter :: JOB_START = -1, JOB_END = -2, JOB_ANALYSE = 1, JOB_FACTORIZE = 2, &
         JOB_SOLVE = 3

   !> First word of a worker command that concerns MUMPS.
   integer, parameter :: MUMPS_SERVICE = 1

   !> One MUMPS instance.  `id` is MUMPS's structure: fill its input
   !! components (N, NNZ, IRN, JCN, A, RHS, ICNTL, CNTL, ...) on the root,
   !! then `run` a job and read INFOG.
   type :: mumps_instance_t
      type(dmumps_struc), pointer :: id => null()   !! MUMPS's structure (null before `start`)
      integer :: key = 0                            !! number of the instance in the run, 0 = none
   contains
      procedure :: start => instance_start
      procedure :: run => instance_run
      procedure :: finish => instance_finish
      procedure :: started => instance_started
   end type mumps_instance_t

   interface
      !> MUMPS's driver (sequential or MPI library, chosen at link time).
      subroutine dmumps(id)
         import :: dmumps_struc
         type(dmumps_struc), intent(inout) :: id
      end subroutine dmumps
   end interface

   !> Workers: their instances, by key.
   type :: worker_slot_t
      integer :: key = 0
      type(dmumps_struc), pointer :: id => null()
   end type worker_slot_t
   type(worker_slot_t), allocatable :: slots(:)
   !> Root: keys handed out so far.
   integer :: last_key = 0

contains

   !> Start an instance (JOB = -1) for a matrix of symmetry `sym` (0
   !! unsymmetric, 1 symmetric positive definite, 2 general symmetric), with
   !! MUMPS silent on the terminal.  On a worker process of an MPI run this
   !! call never returns: the process serves the root's MUMPS calls until the
   !! root ends.  Returns INFOG(1) of the start (0 on success).
   subroutine instance_start(this, sym, info1)
      class(mumps_instance_t), intent(inout) :: this
      integer, intent(in) :: sym        !! MUMPS's SYM
      integer, intent(out) :: info1     !! INFOG(1) after JOB = -1
      call parallel_init()              ! done by the main program; a unit test may not have
      if (.not. is_root()) call serve_commands(serve_mumps)
      if (this%started()) then
         call fatal_internal('mumps: start of a started instance', 'mumps_instance.f90', __LINE__)
      end if
      last_key = last_key + 1
      this%key = last_key
      allocate (this%id)
      this%id%comm = world_comm()
      this%id%sym = sym
      this%id%par = 1
      call this%run(JOB_START)
      info1 = this%id%infog(1)
      ! no output from MUMPS: errors, diagnostics, global information, level
      this%id%icntl(1:4) = [-1, -1, -1, 0]
   end subroutine instance_start

   !> Run one MUMPS job on this instance (collectively in an MPI run).
   subroutine instance_run(this, job)
      class(mumps_instance_t), intent(inout) :: this
      integer, intent(in) :: job   !! MUMPS's JOB
      if (.not. associated(this%id)) call fatal_internal('mumps: job '//itoa(job)// &
                                                         ' on an instance not started', &
                                                         'mumps_instance.f90', __LINE__)
      if (process_count() > 1) then
         call send_command([MUMPS_SERVICE, job, this%key, this%id%sym])
         if (job /= JOB_START) then
            call broadcast(this%id%icntl)
            call broadcast(this%id%cntl)
         end if
      end if
      this%id%job = job
      call dmumps(this%id)
   end subroutine instance_run

   !> End the instance (JOB = -2): MUMPS releases its data.  The arrays the
   !! caller associated with IRN, JCN, A, RHS, COLSCA, ... are the caller's to
   !! deallocate (before or after).  Nothing happens if it was not started.
   subroutine instance_finish(this)
      class(mumps_instance_t), intent(inout) :: this
      if (.not. associated(this%id)) return
      call this%run(JOB_END)
      deallocate (this%id)
      this%id => null()
      this%key = 0
   end subroutine instance_finish

   pure logical function instance_started(this)
      class(mumps_instance_t), intent(in) :: this
      instance_started = associated(this%id)
   end function instance_started

   !> Worker: make the root's MUMPS call on the instance with the same key.
   subroutine serve_mumps(cmd)
      integer, intent(in) :: cmd(:)   !! (MUMPS_SERVICE, job, key, sym)
      integer :: k
      if (size(cmd) /= COMMAND_WORDS .or. cmd(1) /= MUMPS_SERVICE) then
         call fatal_internal('mumps worker: unknown command '//itoa(cmd(1)), &
                             'mumps_instance.f90', __LINE__)
      end if
      if (cmd(2) == JOB_START) then
         k = free_slot()
         slots(k)%key = cmd(3)
         allocate (slots(k)%id)
         slots(k)%id%comm = world_comm()
         slots(k)%id%sym = cmd(4)
         slots(k)%id%par = 1
      else
         k = findloc(slots(:)%key, cmd(3), dim=1)
         if (k == 0) then
            call fatal_internal('mumps worker: no instance '//itoa(cmd(3)), 'mumps_instance.f90', &
                                __LINE__)
         end if
         call broadcast(slots(k)%id%icntl)
         call broadcast(slots(k)%id%cntl)
      end if
      slots(k)%id%job = cmd(2)
      call dmumps(slots(k)%id)
      if (cmd(2) == JOB_END) then
         deallocate (slots(k)%id)
         slots(k)%id => null()
         slots(k)%key = 0
      end if
   end subroutine serve_mumps

   !> Index of an unused worker slot (the table grows as needed).
   integer function free_slot() result(k)
      type(worker_slot_t), allocatable :: more(:)
      if (.not. allocated(slots)) allocate (slots(4))
      k = findloc(slots(:)%key, 0, dim=1)
      if (k > 0) return
      allocate (more(2*size(slots)))
      more(1:size(slots)) = slots
      k = size(slots) + 1
      call move_alloc(more, slots)
   end function free_slot

   !> A size MUMPS reports in an INFO/INFOG entry: positive values are the
   !! size, negative ones millions of it (for sizes past 2^31).
   pure integer(i8) function mumps_size(v)
      integer, intent(in) :: v
      if (v >= 0) then
         mumps_size = int(v, i8)
      else
         mumps_size = -int(v, i8)*1000000_i8
      end if
   end function mumps_size

   !> Meaning of a MUMPS error code INFOG(1) < 0, with INFOG(2).
   !! Ref: MUMPS 5.5 Users' guide, sec. 8.
   function mumps_error_text(info1, info2) result(s)
      integer, intent(in) :: info1, info2
      character(len=:), allocatable :: s
      character(len=:), allocatable :: what
      select case (info1)
      case (-1)
         what = 'an error occurred on MPI process '//itoa(info2)
      case (-2)
         what = 'the number of entries NNZ is out of range ('//itoa(info2)//')'
      case (-3)
         what = 'invalid JOB sequence (internal error: analysis, factorization and solve called &
         &out of order)'
      case (-5, -7)
         what = 'not enough memory for the analysis (allocation of '//count_text(info2)// &
               ' values failed)'
      case (-6)
         what = 'the matrix is structurally singular (structural rank '//itoa(info2)//')'
      case (-8, -9, -14, -15, -17, -20)
         what = 'an internal workspace of MUMPS is too small (ICNTL(14) relaxation exhausted)'
      case (-10)
         what = 'the matrix is numerically singular (a zero pivot after '//itoa(info2)// &
               ' eliminated pivots)'
      case (-11, -12)
         what = 'the internal workspace of MUMPS is too small for the solve'
      case (-13)
         what = 'not enough memory: an allocation of '//count_text(info2)//' values failed'
      case (-16)
         what = 'the number of equations N is out of range ('//itoa(info2)//')'
      case (-19)
         what = 'the memory limit ICNTL(23) is too small'
      case (-22)
         what = 'an input array of MUMPS is missing or too small (array number '//itoa(info2)//')'
      case (-23)
         what = 'MPI was not initialized'
      case (-40)
         what = 'the matrix declared positive definite has a negative or null pivot'
      case (-50, -88)
         what = 'the fill-reducing ordering failed (INFO(2) = '//itoa(info2)//')'
      case (-51, -52)
         what = 'the ordering library cannot handle a graph this large'
      case (-90)
         what = 'out-of-core error'
      case default
         what = 'error INFOG(1) = '//itoa(info1)//', INFOG(2) = '//itoa(info2)// &
               ' (MUMPS Users'' guide, sec. 8)'
      end select
      s = 'MUMPS: '//what
   end function mumps_error_text

   !> A count as MUMPS reports it (negative: millions), in words.
   pure function count_text(v) result(s)
      integer, intent(in) :: v
      character(len=:), allocatable :: s
      if (v >= 0) then
         s = itoa(v)
      else
         s = itoa(-v)//' million'
      end if
   end function count_text
end module mumps_instance
