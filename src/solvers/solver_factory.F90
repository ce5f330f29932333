!> Linear solver from its name in the deck.
!!
!! The driver asks for a solver by name and holds it as
!! `class(linear_solver_t)`; this is the one place that knows the concrete
!! types.  Names are case-insensitive: `skyline`, `dense` and, in builds with
!! UMFPACK, `umfpack`.
!!
!! This file is preprocessed (.F90) because the UMFPACK solver is compiled
!! only when CMake defines KONTAKT2D_HAVE_UMFPACK.
module solver_factory
   use errors, only: status_t, STAT_INPUT
   use linear_solver, only: linear_solver_t
   use skyline_solver, only: skyline_solver_t
   use dense_solver, only: dense_solver_t
! ---------------------------------------------------------------- UMFPACK hook
! The UMFPACK solver lives in module `umfpack_solver` (src/solvers/umfpack_solver.f90,
! type `umfpack_solver_t`) and is compiled only when CMake defines
! KONTAKT2D_HAVE_UMFPACK; K2D_UMFPACK_SOLVER follows that definition.  [UMFPACK-HOOK]
#ifdef KONTAKT2D_HAVE_UMFPACK
#define K2D_UMFPACK_SOLVER 1
#else
#define K2D_UMFPACK_SOLVER 0
#endif
#if K2D_UMFPACK_SOLVER
   use umfpack_solver, only: umfpack_solver_t
#endif
   implicit none
   private

   public :: create_solver, solver_names

contains

   !> Allocate the solver named `name` (case and surrounding blanks ignored).
   !!
   !! Unknown names give STAT_INPUT with a message that lists the valid
   !! names; `solver` is then left unallocated.
   subroutine create_solver(name, solver, status)
      character(len=*), intent(in) :: name                        !! solver name from the deck
      class(linear_solver_t), allocatable, intent(out) :: solver  !! the new, empty solver
      type(status_t), intent(inout) :: status                     !! STAT_INPUT if unknown

      select case (lowercase(trim(adjustl(name))))
      case ('skyline')
         allocate (skyline_solver_t :: solver)
      case ('dense')
         allocate (dense_solver_t :: solver)
      case ('umfpack')
#if K2D_UMFPACK_SOLVER
         allocate (umfpack_solver_t :: solver)
#else
         call status%set(STAT_INPUT, 'linear solver "umfpack" is not available in this build '// &
                         '(built without UMFPACK); valid names are: '//solver_names())
#endif
      case default
         call status%set(STAT_INPUT, 'unknown linear solver "'//trim(adjustl(name))// &
                         '"; valid names are: '//solver_names())
      end select
   end subroutine create_solver

   !> Valid solver names of this build, comma-separated.
   pure function solver_names() result(s)
      character(len=:), allocatable :: s
      s = 'skyline, dense'
#if K2D_UMFPACK_SOLVER
      s = s//', umfpack'
#endif
   end function solver_names

   !> Lower-case copy of an ASCII string.
   pure function lowercase(s) result(r)
      character(len=*), intent(in) :: s
      character(len=len(s)) :: r
      integer :: i, c
      r = s
      do i = 1, len(s)
         c = iachar(s(i:i))
         if (c >= iachar('A') .and. c <= iachar('Z')) r(i:i) = achar(c + 32)
      end do
   end function lowercase
end module solver_factory
