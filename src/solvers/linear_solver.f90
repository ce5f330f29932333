!> Abstract interface of the linear solvers (skyline, UMFPACK, dense).
!!
!! Life cycle, the same for every implementation:
!!
!!     call s%analyse(neq, xadj, adjncy, status)   ! once per sparsity pattern
!!     call s%zero()
!!     call s%add_element(ieq, ke)                 ! many times (K_AB)
!!     call s%store_base()                         ! keep K_AB
!!     do increment
!!        call s%restore_base()                    ! back to K_AB
!!        call s%add_element(ieq, kc)              ! contact springs
!!        call s%factorize(status)
!!        call s%solve(b, status)                  ! many right-hand sides
!!     end do
!!     call s%free()
!!
!! The pattern handed to `analyse` must contain every coupling that will ever
!! be assembled (bodies, ties and all candidate contact pairs), so that the
!! symbolic work is done once.  The driver never knows which solver it holds.
module linear_solver
   use kinds, only: dp, i8
   use errors, only: status_t, fatal_internal, STAT_SOLVER
   use strings, only: itoa
   implicit none
   private

   public :: linear_solver_t, solver_stats_t
   public :: ST_EMPTY, ST_ASSEMBLING, ST_FACTORED, ST_FAILED

   !> Life-cycle states shared by every implementation.
   integer, parameter :: ST_EMPTY = 0       !! no pattern: analyse not called
   integer, parameter :: ST_ASSEMBLING = 1  !! the matrix holds assembled values
   integer, parameter :: ST_FACTORED = 2    !! the factors are valid
   integer, parameter :: ST_FAILED = 3      !! the last factorization failed

   !> Figures every solver reports after a factorization.
   type :: solver_stats_t
      integer :: neq = 0                 !! number of equations
      integer(i8) :: nnz_matrix = 0      !! stored entries of the matrix (one triangle for skyline)
      integer(i8) :: nnz_factor = 0      !! stored entries of the factors
      integer(i8) :: memory_bytes = 0    !! memory held by the solver (matrix + factors)
      integer :: negative_pivots = 0     !! number of negative pivots (skyline)
      real(dp) :: pivot_ratio = 0.0_dp   !! min |d_i| / |k_ii| over the pivots (skyline)
      integer :: factorizations = 0      !! numeric factorizations so far
      integer :: solves = 0              !! solves so far
   end type solver_stats_t

   type, abstract :: linear_solver_t
      integer :: neq = 0
      type(solver_stats_t) :: stats
      !> Bookkeeping common to the implementations (read and set by them only).
      integer :: state = ST_EMPTY
      integer :: bad_eq = 0                      !! equation of the failed pivot
      character(len=:), allocatable :: fail_msg  !! message of the failed factorization
      integer(i8) :: n_outside = 0               !! assembled entries outside the pattern
      integer(i8) :: base_outside = 0            !! the same, at store_base
      integer :: first_outside(2) = 0            !! (row, column) of the first of them
      integer :: base_first_outside(2) = 0
   contains
      procedure(analyse_i), deferred :: analyse
      procedure(zero_i), deferred :: zero
      procedure(add_element_i), deferred :: add_element
      procedure(zero_i), deferred :: store_base
      procedure(zero_i), deferred :: restore_base
      procedure(factorize_i), deferred :: factorize
      procedure(solve_i), deferred :: solve
      procedure(zero_i), deferred :: free
      procedure(name_i), deferred :: name
      procedure :: failed_equation
      procedure :: expect_refactorizations
      procedure :: ordering_note
      procedure :: reset_common
      procedure :: check_element
      procedure :: ready_to_solve
   end type linear_solver_t

   abstract interface
      !> Symbolic set-up from the equation graph.
      subroutine analyse_i(this, neq, xadj, adjncy, status)
         import :: linear_solver_t, status_t
         class(linear_solver_t), intent(inout) :: this
         integer, intent(in) :: neq          !! number of equations
         integer, intent(in) :: xadj(:)      !! (neq+1) CSR row pointers of the graph
         integer, intent(in) :: adjncy(:)    !! columns coupled to each row, diagonal included
         type(status_t), intent(inout) :: status
      end subroutine analyse_i

      subroutine zero_i(this)
         import :: linear_solver_t
         class(linear_solver_t), intent(inout) :: this
      end subroutine zero_i

      !> Add a symmetric element matrix; entries with ieq <= 0 are skipped.
      subroutine add_element_i(this, ieq, ke)
         import :: linear_solver_t, dp
         class(linear_solver_t), intent(inout) :: this
         integer, intent(in) :: ieq(:)       !! global equation of each element dof
         real(dp), intent(in) :: ke(:, :)    !! element matrix, size(ieq) square
      end subroutine add_element_i

      subroutine factorize_i(this, status)
         import :: linear_solver_t, status_t
         class(linear_solver_t), intent(inout) :: this
         type(status_t), intent(inout) :: status
      end subroutine factorize_i

      !> Overwrite b with the solution of K x = b.
      subroutine solve_i(this, b, status)
         import :: linear_solver_t, dp, status_t
         class(linear_solver_t), intent(inout) :: this
         real(dp), intent(inout) :: b(:)
         type(status_t), intent(inout) :: status
      end subroutine solve_i

      function name_i(this) result(s)
         import :: linear_solver_t
         class(linear_solver_t), intent(in) :: this
         character(len=:), allocatable :: s
      end function name_i
   end interface

contains

   !> Hint, after `analyse` and before the first factorization, that the
   !! pattern will be factorized many times (a new set of springs each time),
   !! so that a costlier ordering that makes each factorization cheaper may
   !! pay.  No effect by default; the MUMPS solver chooses its ordering by it.
   subroutine expect_refactorizations(this)
      class(linear_solver_t), intent(inout) :: this
      associate (unused => this)
      end associate
   end subroutine expect_refactorizations

   !> The fill-reducing ordering of the last analysis in words, for the
   !! listing; empty when the solver has no choice of ordering to tell.
   function ordering_note(this) result(s)
      class(linear_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = ''
      associate (unused => this)
      end associate
   end function ordering_note

   !> Equation at which the last factorization failed (0 if none or unknown).
   pure integer function failed_equation(this) result(eq)
      class(linear_solver_t), intent(in) :: this
      eq = this%bad_eq
   end function failed_equation

   !> Reset the common bookkeeping: the solver is as new (statistics too).
   subroutine reset_common(this)
      class(linear_solver_t), intent(inout) :: this
      this%neq = 0
      this%state = ST_EMPTY
      this%bad_eq = 0
      this%fail_msg = ''
      this%n_outside = 0
      this%base_outside = 0
      this%first_outside = 0
      this%base_first_outside = 0
      this%stats = solver_stats_t()
   end subroutine reset_common

   !> Programming errors of `add_element`: called outside assembly, or an
   !! element matrix whose size differs from its equation list.
   subroutine check_element(this, ieq, ke, file, line)
      class(linear_solver_t), intent(in) :: this
      integer, intent(in) :: ieq(:)
      real(dp), intent(in) :: ke(:, :)
      character(len=*), intent(in) :: file   !! source file of the caller
      integer, intent(in) :: line            !! line of the caller
      if (this%state /= ST_ASSEMBLING) call fatal_internal(this%name()// &
         ' solver: add_element outside assembly (call analyse, zero or restore_base first)', &
         file, line)
      if (size(ke, 1) /= size(ieq) .or. size(ke, 2) /= size(ieq)) call fatal_internal( &
         this%name()//' solver: element matrix and equation list differ in size', file, line)
   end subroutine check_element

   !> Can `solve` go ahead with a right-hand side of nb entries?  Otherwise
   !! the status says why (no valid factorization, or the wrong length).
   logical function ready_to_solve(this, nb, status) result(ok)
      class(linear_solver_t), intent(in) :: this
      integer, intent(in) :: nb
      type(status_t), intent(inout) :: status
      ok = .false.
      select case (this%state)
      case (ST_FACTORED)
      case (ST_FAILED)
         call status%set(STAT_SOLVER, this%name()// &
                         ' solver: no valid factorization to solve with ('// &
                         this%fail_msg//')')
         return
      case default
         call status%set(STAT_SOLVER, this%name()//' solver: solve called before factorize')
         return
      end select
      if (nb /= this%neq) then
         call status%set(STAT_SOLVER, this%name()//' solver: right-hand side has '//itoa(nb)// &
                         ' entries, expected '//itoa(this%neq))
         return
      end if
      ok = .true.
   end function ready_to_solve
end module linear_solver
