!> Fallback for the subset of pFUnit 4's `funit` module that Kontakt2D's test suites use.
!!
!! Built only when CMake finds no pFUnit installation (see docs/DEVELOPERS.md). The preprocessor
!! beside this file (pf_preprocess.py) turns every `@assertXxx(args)` directive into
!!
!!     call assertXxx(args, location=SourceLocation('file.pf', line)); if (anyExceptions()) return
!!
!! as pFUnit's own preprocessor does, so the dummy-argument names below, their order, and which
!! of them are keyword-only (those after an `unused` keyword enforcer) are pFUnit's: a directive
!! that compiles against this module compiles against pFUnit. Tolerances, conformability rules
!! and failure messages follow pFUnit 4.14 (src/funit/asserts); the differences are listed in
!! docs/DEVELOPERS.md.
!!
!! Only default-kind and 64-bit integers, default-kind and 64-bit reals, logicals and scalar
!! strings are supported; arrays up to rank 5 are accepted through assumed-rank dummies.
module funit
   use, intrinsic :: iso_fortran_env, only: int64, real64, output_unit, error_unit
   use, intrinsic :: ieee_exceptions, only: ieee_status_type, ieee_get_status, ieee_set_status, &
      ieee_set_halting_mode, ieee_usual
   implicit none
   private

   ! pFUnit's names (the supported subset).
   public :: SourceLocation
   public :: assertEqual, assertRelativelyEqual
   public :: assertTrue, assertFalse, assertAll, assertAny
   public :: assertLessThan, assertLessThanOrEqual
   public :: assertGreaterThan, assertGreaterThanOrEqual
   public :: assertExceptionRaised
   public :: throw, catch, anyExceptions

   ! Used only by the code that pf_preprocess.py generates.
   public :: pff_test_procedure, pff_initialize, pff_run_test, pff_finalize

   integer, parameter :: dp = real64
   integer, parameter :: i8 = int64

   !> Where an assertion was written: the `.pf` file's base name and the directive's line.
   type :: SourceLocation
      character(len=255) :: fileName = '<unknown file>'
      integer :: lineNumber = -1
   end type SourceLocation

   !> Makes the arguments after it keyword-only, as pFUnit's KeywordEnforcer does.
   type :: keyword_enforcer_t
   end type keyword_enforcer_t

   !> One failed assertion of the running test (pFUnit's Exception).
   type :: exception_t
      character(len=:), allocatable :: message
      type(SourceLocation) :: location
   end type exception_t

   abstract interface
      !> A test method, or the `@before` / `@after` fixture of its module.
      subroutine pff_test_procedure()
      end subroutine pff_test_procedure
   end interface

   ! Comparison codes shared by the real and integer kernels.
   integer, parameter :: op_equal = 1, op_relative = 2, op_less = 3, op_less_equal = 4, &
                         op_greater = 5, op_greater_equal = 6
   integer, parameter :: max_rank = 5
   integer, parameter :: len_value = 45   ! pFUnit's MAX_LEN_REAL_AS_STRING
   character(len=*), parameter :: nl = new_line('a')

   ! Exceptions thrown by the running test; cleared before each test.
   type(exception_t), allocatable :: pending(:)
   integer :: n_pending = 0

   ! Runner state.
   logical :: verbose = .false.
   character(len=:), allocatable :: name_filter
   character(len=:), allocatable :: report
   integer :: n_run = 0, n_failed = 0, column = 0
   integer(i8) :: clock_start = 0

   interface assertEqual
      module procedure assert_equal_int_int, assert_equal_i8_i8, assert_equal_int_i8
      module procedure assert_equal_int_dp, assert_equal_real_dp, assert_equal_dp_dp
      module procedure assert_equal_int_dp_tol_real, assert_equal_real_dp_tol_real, &
                       assert_equal_dp_dp_tol_real
      module procedure assert_equal_int_dp_tol_dp, assert_equal_real_dp_tol_dp, &
                       assert_equal_dp_dp_tol_dp
      module procedure assert_equal_logical, assert_equal_string
   end interface assertEqual

   interface assertRelativelyEqual
      module procedure assert_rel_int_dp_tol_real, assert_rel_real_dp_tol_real, &
                       assert_rel_dp_dp_tol_real
      module procedure assert_rel_int_dp_tol_dp, assert_rel_real_dp_tol_dp, &
                       assert_rel_dp_dp_tol_dp
   end interface assertRelativelyEqual

   interface assertLessThan
      module procedure assert_lt_int_int, assert_lt_i8_i8, assert_lt_int_i8
      module procedure assert_lt_int_dp, assert_lt_real_dp, assert_lt_dp_dp
   end interface assertLessThan

   interface assertLessThanOrEqual
      module procedure assert_le_int_int, assert_le_i8_i8, assert_le_int_i8
      module procedure assert_le_int_dp, assert_le_real_dp, assert_le_dp_dp
   end interface assertLessThanOrEqual

   interface assertGreaterThan
      module procedure assert_gt_int_int, assert_gt_i8_i8, assert_gt_int_i8
      module procedure assert_gt_int_dp, assert_gt_real_dp, assert_gt_dp_dp
   end interface assertGreaterThan

   interface assertGreaterThanOrEqual
      module procedure assert_ge_int_int, assert_ge_i8_i8, assert_ge_int_i8
      module procedure assert_ge_int_dp, assert_ge_real_dp, assert_ge_dp_dp
   end interface assertGreaterThanOrEqual

   interface assertTrue
      module procedure assert_true_scalar, assert_true_1d
   end interface assertTrue

   interface assertFalse
      module procedure assert_false_scalar, assert_false_1d
   end interface assertFalse

   interface assertExceptionRaised
      module procedure assert_exception_raised_any, assert_exception_raised_message
   end interface assertExceptionRaised

   interface catch
      module procedure catch_any, catch_message
   end interface catch

   ! Flatten an assumed-rank argument (rank 0 to max_rank) into a rank-1 array.
   interface as_dp
      module procedure as_dp_from_int, as_dp_from_real, as_dp_from_dp
   end interface as_dp

   interface as_i8
      module procedure as_i8_from_int, as_i8_from_i8
   end interface as_i8

contains

   ! ======================================================================= assertEqual

   subroutine assert_equal_int_int(expected, actual, message, location)
      integer, intent(in) :: expected(..), actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_int(op_equal, as_i8(expected), shape(expected), as_i8(actual), shape(actual), &
                     message, location)
   end subroutine assert_equal_int_int

   subroutine assert_equal_i8_i8(expected, actual, message, location)
      integer(i8), intent(in) :: expected(..), actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_int(op_equal, as_i8(expected), shape(expected), as_i8(actual), shape(actual), &
                     message, location)
   end subroutine assert_equal_i8_i8

   subroutine assert_equal_int_i8(expected, actual, message, location)
      integer, intent(in) :: expected(..)
      integer(i8), intent(in) :: actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_int(op_equal, as_i8(expected), shape(expected), as_i8(actual), shape(actual), &
                     message, location)
   end subroutine assert_equal_int_i8

   subroutine assert_equal_int_dp(expected, actual, message, location)
      integer, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      0.0_dp, message, location)
   end subroutine assert_equal_int_dp

   subroutine assert_equal_real_dp(expected, actual, message, location)
      real, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      0.0_dp, message, location)
   end subroutine assert_equal_real_dp

   subroutine assert_equal_dp_dp(expected, actual, message, location)
      real(dp), intent(in) :: expected(..), actual(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      0.0_dp, message, location)
   end subroutine assert_equal_dp_dp

   subroutine assert_equal_int_dp_tol_real(expected, actual, tolerance, message, location)
      integer, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      real(tolerance, dp), message, location)
   end subroutine assert_equal_int_dp_tol_real

   subroutine assert_equal_real_dp_tol_real(expected, actual, tolerance, message, location)
      real, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      real(tolerance, dp), message, location)
   end subroutine assert_equal_real_dp_tol_real

   subroutine assert_equal_dp_dp_tol_real(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(..), actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      real(tolerance, dp), message, location)
   end subroutine assert_equal_dp_dp_tol_real

   subroutine assert_equal_int_dp_tol_dp(expected, actual, tolerance, message, location)
      integer, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      tolerance, message, location)
   end subroutine assert_equal_int_dp_tol_dp

   subroutine assert_equal_real_dp_tol_dp(expected, actual, tolerance, message, location)
      real, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      tolerance, message, location)
   end subroutine assert_equal_real_dp_tol_dp

   subroutine assert_equal_dp_dp_tol_dp(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(..), actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_equal, as_dp(expected), shape(expected), as_dp(actual), shape(actual), &
                      tolerance, message, location)
   end subroutine assert_equal_dp_dp_tol_dp

   !> Logical equality is pFUnit's AssertEquivalent (`.eqv.`), with its failure text.
   subroutine assert_equal_logical(expected, actual, unused, message, location)
      logical, intent(in) :: expected(..), actual(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      logical, allocatable :: e(:), a(:)
      integer :: k

      if (present(unused)) continue
      if (.not. conformable(shape(expected), shape(actual), message, location)) return
      allocate (a(size(actual)), e(size(actual)))
      a(:) = as_lgc(actual)
      if (rank(expected) == 0) then
         e(:) = any(as_lgc(expected))   ! the scalar's value, spread over actual's shape
      else
         e(:) = as_lgc(expected)
      end if
      k = first_false(e .eqv. a)
      if (k == 0) return
      ! pFUnit closes the index line of this message with a stray '>'; kept for identical text.
      call throw(base_message('AssertEquivalent', message, rank(actual) > 0) &
                 // nl // '    Expected: <' // merge('T', 'F', e(k)) // '>' &
                 // nl // '    Actual:   <' // merge('T', 'F', a(k)) // '>' &
                 // index_line('    at index: ', k, shape(actual)) &
                 // trim(merge('>', ' ', rank(actual) > 0)), location)
   end subroutine assert_equal_logical

   !> String equality ignoring leading and trailing blanks and tabs (pFUnit's default TRIM_ALL).
   subroutine assert_equal_string(expected, found, message, location)
      character(*), intent(in) :: expected, found
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      character(len=:), allocatable :: e, f, text
      integer :: n_same

      e = trim_all(expected)
      f = trim_all(found)
      if (len(e) == len(f)) then
         if (e == f) return
      end if
      n_same = 0
      do while (n_same < min(len(e), len(f)))
         if (e(n_same + 1:n_same + 1) /= f(n_same + 1:n_same + 1)) exit
         n_same = n_same + 1
      end do
      text = 'String assertion failed:' &
             // nl // '    expected: <"' // trim_trailing(expected) // '">' &
             // nl // '   but found: <"' // trim_trailing(found) // '">' &
             // nl // '  first diff:   ' // repeat('-', n_same) // '^'
      if (present(message)) then
         if (len_trim(message) > 0) text = trim(message) // ' ' // text
      end if
      call throw(text, location)
   end subroutine assert_equal_string

   ! ======================================================================= assertRelativelyEqual

   subroutine assert_rel_int_dp_tol_real(expected, actual, tolerance, message, location)
      integer, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), real(tolerance, dp), message, location)
   end subroutine assert_rel_int_dp_tol_real

   subroutine assert_rel_real_dp_tol_real(expected, actual, tolerance, message, location)
      real, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), real(tolerance, dp), message, location)
   end subroutine assert_rel_real_dp_tol_real

   subroutine assert_rel_dp_dp_tol_real(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(..), actual(..)
      real, intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), real(tolerance, dp), message, location)
   end subroutine assert_rel_dp_dp_tol_real

   subroutine assert_rel_int_dp_tol_dp(expected, actual, tolerance, message, location)
      integer, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), tolerance, message, location)
   end subroutine assert_rel_int_dp_tol_dp

   subroutine assert_rel_real_dp_tol_dp(expected, actual, tolerance, message, location)
      real, intent(in) :: expected(..)
      real(dp), intent(in) :: actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), tolerance, message, location)
   end subroutine assert_rel_real_dp_tol_dp

   subroutine assert_rel_dp_dp_tol_dp(expected, actual, tolerance, message, location)
      real(dp), intent(in) :: expected(..), actual(..)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_relative, as_dp(expected), shape(expected), as_dp(actual), &
                      shape(actual), tolerance, message, location)
   end subroutine assert_rel_dp_dp_tol_dp

   ! ======================================================================= orderings
   ! lhs may be a scalar or have the shape of rhs. Integer forms take message= by keyword only,
   ! as in pFUnit; real forms also accept it in third position.

   subroutine assert_lt_int_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), message, location)
   end subroutine assert_lt_int_int

   subroutine assert_lt_i8_i8(lhs, rhs, unused, message, location)
      integer(i8), intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), message, location)
   end subroutine assert_lt_i8_i8

   subroutine assert_lt_int_i8(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..)
      integer(i8), intent(in) :: rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), message, location)
   end subroutine assert_lt_int_i8

   subroutine assert_lt_int_dp(lhs, rhs, message, location)
      integer, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_lt_int_dp

   subroutine assert_lt_real_dp(lhs, rhs, message, location)
      real, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_lt_real_dp

   subroutine assert_lt_dp_dp(lhs, rhs, message, location)
      real(dp), intent(in) :: lhs(..), rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_lt_dp_dp

   subroutine assert_le_int_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_le_int_int

   subroutine assert_le_i8_i8(lhs, rhs, unused, message, location)
      integer(i8), intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_le_i8_i8

   subroutine assert_le_int_i8(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..)
      integer(i8), intent(in) :: rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_less_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_le_int_i8

   subroutine assert_le_int_dp(lhs, rhs, message, location)
      integer, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_le_int_dp

   subroutine assert_le_real_dp(lhs, rhs, message, location)
      real, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_le_real_dp

   subroutine assert_le_dp_dp(lhs, rhs, message, location)
      real(dp), intent(in) :: lhs(..), rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_less_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_le_dp_dp

   subroutine assert_gt_int_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_gt_int_int

   subroutine assert_gt_i8_i8(lhs, rhs, unused, message, location)
      integer(i8), intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_gt_i8_i8

   subroutine assert_gt_int_i8(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..)
      integer(i8), intent(in) :: rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_gt_int_i8

   subroutine assert_gt_int_dp(lhs, rhs, message, location)
      integer, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_gt_int_dp

   subroutine assert_gt_real_dp(lhs, rhs, message, location)
      real, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_gt_real_dp

   subroutine assert_gt_dp_dp(lhs, rhs, message, location)
      real(dp), intent(in) :: lhs(..), rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), 0.0_dp, &
                      message, location)
   end subroutine assert_gt_dp_dp

   subroutine assert_ge_int_int(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_ge_int_int

   subroutine assert_ge_i8_i8(lhs, rhs, unused, message, location)
      integer(i8), intent(in) :: lhs(..), rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_ge_i8_i8

   subroutine assert_ge_int_i8(lhs, rhs, unused, message, location)
      integer, intent(in) :: lhs(..)
      integer(i8), intent(in) :: rhs(..)
      class(keyword_enforcer_t), optional, intent(in) :: unused
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (present(unused)) continue
      call check_int(op_greater_equal, as_i8(lhs), shape(lhs), as_i8(rhs), shape(rhs), &
                     message, location)
   end subroutine assert_ge_int_i8

   subroutine assert_ge_int_dp(lhs, rhs, message, location)
      integer, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), &
                      0.0_dp, message, location)
   end subroutine assert_ge_int_dp

   subroutine assert_ge_real_dp(lhs, rhs, message, location)
      real, intent(in) :: lhs(..)
      real(dp), intent(in) :: rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), &
                      0.0_dp, message, location)
   end subroutine assert_ge_real_dp

   subroutine assert_ge_dp_dp(lhs, rhs, message, location)
      real(dp), intent(in) :: lhs(..), rhs(..)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      call check_real(op_greater_equal, as_dp(lhs), shape(lhs), as_dp(rhs), shape(rhs), &
                      0.0_dp, message, location)
   end subroutine assert_ge_dp_dp

   ! ======================================================================= logical conditions

   !> Without message= a failure has an empty text, as in pFUnit; the location still names it.
   subroutine assert_true_scalar(condition, message, location)
      logical, intent(in) :: condition
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (.not. condition) call throw(optional_text(message), location)
   end subroutine assert_true_scalar

   subroutine assert_true_1d(condition, message, location)
      logical, intent(in) :: condition(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (.not. all(condition)) call throw(optional_text(message), location)
   end subroutine assert_true_1d

   subroutine assert_false_scalar(condition, message, location)
      logical, intent(in) :: condition
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (condition) call throw(optional_text(message), location)
   end subroutine assert_false_scalar

   subroutine assert_false_1d(condition, message, location)
      logical, intent(in) :: condition(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (any(condition)) call throw(optional_text(message), location)
   end subroutine assert_false_1d

   subroutine assertAll(conditions, message, location)
      logical, intent(in) :: conditions(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (.not. all(conditions)) call throw(optional_text(message), location)
   end subroutine assertAll

   subroutine assertAny(conditions, message, location)
      logical, intent(in) :: conditions(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (.not. any(conditions)) call throw(optional_text(message), location)
   end subroutine assertAny

   ! ======================================================================= exceptions

   !> Records a failure of the running test (pFUnit's throw).
   subroutine throw(message, location)
      character(*), intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      type(exception_t), allocatable :: grown(:)
      integer :: i

      if (.not. allocated(pending)) allocate (pending(4))
      if (n_pending == size(pending)) then
         allocate (grown(2*size(pending)))
         do i = 1, n_pending
            call move_alloc(pending(i)%message, grown(i)%message)
            grown(i)%location = pending(i)%location
         end do
         call move_alloc(grown, pending)
      end if
      n_pending = n_pending + 1
      pending(n_pending)%message = message
      if (present(location)) then
         pending(n_pending)%location = location
      else
         pending(n_pending)%location = SourceLocation()
      end if
   end subroutine throw

   !> True if the running test has failed so far (pFUnit's anyExceptions).
   logical function anyExceptions()
      anyExceptions = n_pending > 0
   end function anyExceptions

   !> Removes the most recent failure, if any; true if there was one.
   logical function catch_any(preserve) result(found)
      logical, optional, intent(in) :: preserve
      found = n_pending > 0
      if (found .and. .not. keep(preserve)) n_pending = n_pending - 1
   end function catch_any

   !> Removes the first failure whose text equals message; true if there was one.
   logical function catch_message(message, preserve) result(found)
      character(*), intent(in) :: message
      logical, optional, intent(in) :: preserve
      integer :: i, j

      found = .false.
      do i = 1, n_pending
         if (pending(i)%message == message) then
            found = .true.
            if (.not. keep(preserve)) then
               do j = i, n_pending - 1
                  call move_alloc(pending(j + 1)%message, pending(j)%message)
                  pending(j)%location = pending(j + 1)%location
               end do
               n_pending = n_pending - 1
            end if
            return
         end if
      end do
   end function catch_message

   subroutine assert_exception_raised_any(location)
      type(SourceLocation), optional, intent(in) :: location
      if (.not. catch()) call throw('Failed to throw exception.', location)
   end subroutine assert_exception_raised_any

   subroutine assert_exception_raised_message(message, location)
      character(*), intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      if (.not. catch(message)) &
         call throw('Failed to throw exception: <' // trim(message) // '>', location)
   end subroutine assert_exception_raised_message

   ! ======================================================================= runner

   !> Reads the command line: -v/--verbose (also -d/--debug) and -f/--filter PATTERN, as
   !! pFUnit's driver does; other pFUnit options are refused with a message.
   subroutine pff_initialize()
      character(len=:), allocatable :: arg
      integer :: i, n

      n = command_argument_count()
      i = 1
      do while (i <= n)
         arg = command_argument(i)
         select case (arg)
         case ('-v', '--verbose', '-d', '--debug')
            verbose = .true.
         case ('-f', '--filter')
            if (i == n) then
               write (error_unit, '(a)') 'pFUnit fallback: ' // arg // ' needs a pattern'
               error stop 1
            end if
            i = i + 1
            name_filter = command_argument(i)
         case ('-h', '--help')
            write (output_unit, '(a)') 'usage: <suite> [-h] [-v] [-f PATTERN]', &
               '  -v, -d, --verbose, --debug  print the start and end of every test', &
               '  -f, --filter PATTERN        run only tests whose name contains PATTERN'
            stop
         case default
            write (error_unit, '(a)') 'pFUnit fallback: unsupported option ' // arg &
               // ' (supported: -v, -f PATTERN, -h)'
            error stop 1
         end select
         i = i + 1
      end do
      report = ''
      call system_clock(clock_start)
   end subroutine pff_initialize

   !> Runs one test as pFUnit's TestCase%runBare does: set_up; if it raised nothing, the test
   !! and then tear_down. Prints a dot, and an F when the test failed.
   subroutine pff_run_test(suite_name, test_name, test, set_up, tear_down)
      character(*), intent(in) :: suite_name
      character(*), intent(in) :: test_name
      procedure(pff_test_procedure) :: test
      procedure(pff_test_procedure), optional :: set_up, tear_down
      character(len=:), allocatable :: full_name
      integer :: i

      full_name = suite_name // '.' // test_name
      if (allocated(name_filter)) then
         if (index(full_name, name_filter) == 0) return
      end if
      if (verbose) write (output_unit, '(/,a)') ' Start: <' // full_name // '>'
      call put_mark('.')
      n_run = n_run + 1
      n_pending = 0
      if (present(set_up)) call set_up()
      if (.not. anyExceptions()) then
         call test()
         if (present(tear_down)) call tear_down()
      end if
      if (n_pending > 0) then
         if (verbose) write (output_unit, '(a)') ' Failure in <' // full_name // '>'
         call put_mark('F')
         n_failed = n_failed + 1
         do i = 1, n_pending
            report = report // 'Failure in: ' // full_name // nl &
                     // '  Location: ' // location_text(pending(i)%location) // nl &
                     // pending(i)%message // nl // ' ' // nl
         end do
         n_pending = 0
      end if
      if (verbose) write (output_unit, '(a)') '   end: <' // full_name // '>'
      flush (output_unit)
   end subroutine pff_run_test

   !> Prints the failures and pFUnit's summary; exits with status 2 if any test failed.
   subroutine pff_finalize()
      integer(i8) :: clock_now, clock_rate
      real :: seconds

      call system_clock(clock_now, clock_rate)
      seconds = real(clock_now - clock_start) / real(max(clock_rate, 1_i8))
      write (output_unit, '(a)') ''
      write (output_unit, '(a,1x,f12.3,1x,a)') 'Time: ', seconds, 'seconds'
      write (output_unit, '(a)') ' '
      write (output_unit, '(a)', advance='no') report
      if (n_failed == 0) then
         write (output_unit, '(a)') ' OK'
         write (output_unit, '(a,i0,a)') ' (', n_run, trim(merge(' tests)', ' test) ', n_run > 1))
      else
         write (output_unit, '(a)') ' FAILURES!!!'
         write (output_unit, '(a,i0,a,i0,a)') 'Tests run: ', n_run, ', Failures: ', n_failed, &
            ', Errors: 0, Disabled: 0'
         write (output_unit, '(a)') '*** Encountered 1 or more failures/errors during testing ***'
         flush (output_unit)
         stop 2
      end if
   end subroutine pff_finalize

   subroutine put_mark(mark)
      character, intent(in) :: mark
      write (output_unit, '(a)', advance='no') mark
      column = column + 1
      if (column >= 80) then
         write (output_unit, '(a)') ''
         column = 0
      end if
   end subroutine put_mark

   ! ======================================================================= kernels

   !> Compares reals as pFUnit does, in double precision. Ref: pFUnit Assert_Real.tmpl.
   !!   equal:    a == e  or  |a - e| <= tol          (tol = 0 without tolerance=)
   !!   relative: |a - e| <= tol*|e|, any e == 0 is itself a failure
   !!   lt/le/gt/ge: lhs < rhs + tol, lhs <= rhs + tol, lhs > rhs - tol, lhs >= rhs - tol
   !! e (or lhs) is either a scalar or has the shape of a (or rhs); the first element in
   !! array-element order that fails is reported, with its index if a is an array.
   !! Floating-point traps are held off while comparing, so a NaN or an overflow in the
   !! difference is reported as a failure instead of stopping the run.
   subroutine check_real(op, e_in, e_shape, a, a_shape, tolerance, message, location)
      integer, intent(in) :: op
      real(dp), intent(in) :: e_in(:), a(:)
      integer, intent(in) :: e_shape(:), a_shape(:)
      real(dp), intent(in) :: tolerance
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      real(dp), allocatable :: e(:)
      type(ieee_status_type) :: fp_status
      character(len=len_value) :: e_str, a_str
      character(len=3*len_value) :: d_str
      logical :: zero_denominator
      integer :: k

      if (.not. ranks_supported(e_shape, a_shape, location)) return
      if (.not. conformable(e_shape, a_shape, message, location)) return
      allocate (e(size(a)))
      if (size(e_shape) == 0) then
         e(:) = e_in(1)
      else
         e(:) = e_in
      end if

      call ieee_get_status(fp_status)
      call ieee_set_halting_mode(ieee_usual, .false.)
      zero_denominator = .false.
      k = 0
      d_str = ''
      if (op == op_relative) zero_denominator = any(abs(e) <= 0.0_dp)
      if (.not. zero_denominator) k = first_false(real_ok(op, e, a, tolerance))
      if (k > 0) then
         write (e_str, '(g0)') e(k)
         write (a_str, '(g0)') a(k)
         if (op == op_equal) then
            write (d_str, '("<",g0,"> (greater than tolerance of ",g0,")")') a(k) - e(k), tolerance
         else if (op == op_relative) then
            write (d_str, '("<",g0,"> (greater than tolerance of ",g0,")")') &
               (a(k) - e(k)) / e(k), tolerance
         end if
      end if
      call ieee_set_status(fp_status)

      if (zero_denominator) then
         call throw(base_message('Zero denominator detected in AssertRelativelyEqual.', &
                                 message, .false.), location)
      else if (k > 0) then
         call throw(failure_text(op, trim(e_str), trim(a_str), trim(d_str), k, a_shape, &
                                 message), location)
      end if
   end subroutine check_real

   elemental logical function real_ok(op, e, a, tol)
      integer, intent(in) :: op
      real(dp), intent(in) :: e, a, tol
      select case (op)
      case (op_equal)
         ! Exact equality first, so that equal infinities pass (pFUnit does the same).
         real_ok = (a <= e .and. a >= e) .or. abs(a - e) <= tol
      case (op_relative)
         real_ok = abs(a - e) <= tol * abs(e)
      case (op_less)
         real_ok = e < a + tol
      case (op_less_equal)
         real_ok = e <= a + tol
      case (op_greater)
         real_ok = e > a - tol
      case default
         real_ok = e >= a - tol
      end select
   end function real_ok

   !> Compares integers exactly, in 64 bits. Ref: pFUnit Assert_Integer.tmpl.
   subroutine check_int(op, e_in, e_shape, a, a_shape, message, location)
      integer, intent(in) :: op
      integer(i8), intent(in) :: e_in(:), a(:)
      integer, intent(in) :: e_shape(:), a_shape(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location
      integer(i8), allocatable :: e(:)
      character(len=len_value) :: e_str, a_str, d_str
      integer :: k

      if (.not. ranks_supported(e_shape, a_shape, location)) return
      if (.not. conformable(e_shape, a_shape, message, location)) return
      allocate (e(size(a)))
      if (size(e_shape) == 0) then
         e(:) = e_in(1)
      else
         e(:) = e_in
      end if
      k = first_false(int_ok(op, e, a))
      if (k == 0) return
      write (e_str, '(i0)') e(k)
      write (a_str, '(i0)') a(k)
      write (d_str, '("<",i0,">")') a(k) - e(k)
      call throw(failure_text(op, trim(e_str), trim(a_str), trim(d_str), k, a_shape, message), &
                 location)
   end subroutine check_int

   elemental logical function int_ok(op, e, a)
      integer, intent(in) :: op
      integer(i8), intent(in) :: e, a
      select case (op)
      case (op_equal)
         int_ok = e == a
      case (op_less)
         int_ok = e < a
      case (op_less_equal)
         int_ok = e <= a
      case (op_greater)
         int_ok = e > a
      case default
         int_ok = e >= a
      end select
   end function int_ok

   !> pFUnit's failure text for a comparison: fail_not_equal, fail_not_less_than, ...
   function failure_text(op, e_str, a_str, d_str, k, a_shape, message) result(text)
      integer, intent(in) :: op
      character(*), intent(in) :: e_str, a_str, d_str
      integer, intent(in) :: k
      integer, intent(in) :: a_shape(:)
      character(*), optional, intent(in) :: message
      character(len=:), allocatable :: text
      logical :: is_array

      is_array = size(a_shape) > 0
      select case (op)
      case (op_equal)
         text = base_message('AssertEqual', message, is_array) &
                // nl // '      Expected: <' // e_str // '>' &
                // nl // '        Actual: <' // a_str // '>' &
                // nl // '    Difference: ' // d_str &
                // index_line('      at index: ', k, a_shape)
      case (op_relative)
         text = base_message('AssertRelativelyEqual', message, is_array) &
                // nl // '           Expected: <' // e_str // '>' &
                // nl // '             Actual: <' // a_str // '>' &
                // nl // '    Rel. difference: ' // d_str &
                // index_line('      at index: ', k, a_shape)
      case (op_less)
         text = base_message('AssertLessThan', message, is_array) &
                // nl // '              LHS: <' // e_str // '>' &
                // nl // '    not less than: <' // a_str // '>' &
                // index_line('         at index: ', k, a_shape)
      case (op_less_equal)
         text = base_message('AssertLessThanOrEqual', message, is_array) &
                // nl // '                          LHS: <' // e_str // '>' &
                // nl // '    not less than or equal to: <' // a_str // '>' &
                // index_line('                     at index: ', k, a_shape)
      case (op_greater)
         text = base_message('AssertGreaterThan', message, is_array) &
                // nl // '                 LHS: <' // e_str // '>' &
                // nl // '    not greater than: <' // a_str // '>' &
                // index_line('            at index: ', k, a_shape)
      case default
         text = base_message('AssertGreaterThanOrEqual', message, is_array) &
                // nl // '                             LHS: <' // e_str // '>' &
                // nl // '    not greater than or equal to: <' // a_str // '>' &
                // index_line('                        at index: ', k, a_shape)
      end select
   end function failure_text

   !> pFUnit's base_message: the user's message on its own line, then "[Array]Kind failure:".
   function base_message(failure_type, message, is_array) result(text)
      character(*), intent(in) :: failure_type
      character(*), optional, intent(in) :: message
      logical, intent(in) :: is_array
      character(len=:), allocatable :: text

      text = ''
      if (present(message)) text = message // nl
      if (is_array) text = text // 'Array'
      text = text // failure_type // ' failure:'
   end function base_message

   !> Scalars conform with anything; arrays must have equal shapes. Unlike pFUnit, where a
   !! scalar actual with an array expected does not compile, here it fails at run time.
   logical function conformable(e_shape, a_shape, message, location)
      integer, intent(in) :: e_shape(:), a_shape(:)
      character(*), optional, intent(in) :: message
      type(SourceLocation), optional, intent(in) :: location

      if (size(e_shape) == 0) then
         conformable = .true.
      else if (size(e_shape) /= size(a_shape)) then
         conformable = .false.
      else
         conformable = all(e_shape == a_shape)
      end if
      if (.not. conformable) &
         call throw(base_message('Arrays not conformable', message, .false.) &
                    // nl // '    Expected shape: ' // int_list(e_shape) &
                    // nl // '      Actual shape: ' // int_list(a_shape), location)
   end function conformable

   logical function ranks_supported(e_shape, a_shape, location)
      integer, intent(in) :: e_shape(:), a_shape(:)
      type(SourceLocation), optional, intent(in) :: location
      ranks_supported = max(size(e_shape), size(a_shape)) <= max_rank
      if (.not. ranks_supported) &
         call throw('pFUnit fallback: arrays of rank above 5 are not supported', location)
   end function ranks_supported

   ! ======================================================================= helpers

   !> "\n<label>[i,j,...]" for the k-th element (array-element order) of an array of shape
   !! a_shape; nothing for a scalar.
   function index_line(label, k, a_shape) result(text)
      character(*), intent(in) :: label
      integer, intent(in) :: k
      integer, intent(in) :: a_shape(:)
      character(len=:), allocatable :: text
      integer :: subscripts(size(a_shape)), j, rest

      text = ''
      if (size(a_shape) == 0) return
      rest = k - 1
      do j = 1, size(a_shape)
         subscripts(j) = mod(rest, a_shape(j)) + 1
         rest = rest / a_shape(j)
      end do
      text = nl // label // int_list(subscripts)
   end function index_line

   !> pFUnit's toString for a shape or an index: "[2,1]"; "[0]" for an empty list.
   function int_list(values) result(text)
      integer, intent(in) :: values(:)
      character(len=:), allocatable :: text
      character(len=12) :: buffer
      integer :: j

      if (size(values) == 0) then
         text = '[0]'
         return
      end if
      text = '['
      do j = 1, size(values)
         write (buffer, '(i0)') values(j)
         text = text // trim(buffer)
         if (j < size(values)) text = text // ','
      end do
      text = text // ']'
   end function int_list

   function location_text(location) result(text)
      type(SourceLocation), intent(in) :: location
      character(len=:), allocatable :: text
      character(len=12) :: buffer

      if (location%lineNumber == -1) then
         text = '[' // trim(location%fileName) // ']'
      else
         write (buffer, '(i0)') location%lineNumber
         text = '[' // trim(location%fileName) // ':' // trim(buffer) // ']'
      end if
   end function location_text

   function optional_text(message) result(text)
      character(*), optional, intent(in) :: message
      character(len=:), allocatable :: text
      text = ''
      if (present(message)) text = trim(message)
   end function optional_text

   logical function keep(preserve)
      logical, optional, intent(in) :: preserve
      keep = .false.
      if (present(preserve)) keep = preserve
   end function keep

   !> Position of the first .false. element, 0 if there is none.
   pure integer function first_false(ok)
      logical, intent(in) :: ok(:)
      integer :: i
      first_false = 0
      do i = 1, size(ok)
         if (.not. ok(i)) then
            first_false = i
            return
         end if
      end do
   end function first_false

   !> pFUnit's whitespace: blank and horizontal tab.
   pure logical function is_blank(c)
      character, intent(in) :: c
      is_blank = c == ' ' .or. iachar(c) == 9
   end function is_blank

   pure function trim_all(s) result(t)
      character(*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: first, last
      first = 1
      do while (first <= len(s))
         if (.not. is_blank(s(first:first))) exit
         first = first + 1
      end do
      last = len(s)
      do while (last >= first)
         if (.not. is_blank(s(last:last))) exit
         last = last - 1
      end do
      t = s(first:last)
   end function trim_all

   pure function trim_trailing(s) result(t)
      character(*), intent(in) :: s
      character(len=:), allocatable :: t
      integer :: last
      last = len(s)
      do while (last >= 1)
         if (.not. is_blank(s(last:last))) exit
         last = last - 1
      end do
      t = s(1:last)
   end function trim_trailing

   function command_argument(i) result(arg)
      integer, intent(in) :: i
      character(len=:), allocatable :: arg
      integer :: n
      call get_command_argument(i, length=n)
      allocate (character(len=n) :: arg)
      if (n > 0) call get_command_argument(i, arg)
   end function command_argument

   ! ----------------------------------------------------------------------- flattening

   pure function as_dp_from_int(x) result(v)
      integer, intent(in) :: x(..)
      real(dp), allocatable :: v(:)
      select rank (x)
      rank (0)
         v = [real(x, dp)]
      rank (1)
         v = real(x, dp)
      rank (2)
         v = real(reshape(x, [size(x)]), dp)
      rank (3)
         v = real(reshape(x, [size(x)]), dp)
      rank (4)
         v = real(reshape(x, [size(x)]), dp)
      rank (5)
         v = real(reshape(x, [size(x)]), dp)
      rank default
         allocate (v(0))
      end select
   end function as_dp_from_int

   pure function as_dp_from_real(x) result(v)
      real, intent(in) :: x(..)
      real(dp), allocatable :: v(:)
      select rank (x)
      rank (0)
         v = [real(x, dp)]
      rank (1)
         v = real(x, dp)
      rank (2)
         v = real(reshape(x, [size(x)]), dp)
      rank (3)
         v = real(reshape(x, [size(x)]), dp)
      rank (4)
         v = real(reshape(x, [size(x)]), dp)
      rank (5)
         v = real(reshape(x, [size(x)]), dp)
      rank default
         allocate (v(0))
      end select
   end function as_dp_from_real

   pure function as_dp_from_dp(x) result(v)
      real(dp), intent(in) :: x(..)
      real(dp), allocatable :: v(:)
      ! allocated before the assignments: gfortran 12's reallocation of an unallocated
      ! result from an assumed-rank section reads uninitialised bounds (UBSan reports it)
      allocate (v(size(x)))
      select rank (x)
      rank (0)
         v = [x]
      rank (1)
         v = x
      rank (2)
         v = reshape(x, [size(x)])
      rank (3)
         v = reshape(x, [size(x)])
      rank (4)
         v = reshape(x, [size(x)])
      rank (5)
         v = reshape(x, [size(x)])
      rank default
         allocate (v(0))
      end select
   end function as_dp_from_dp

   pure function as_i8_from_int(x) result(v)
      integer, intent(in) :: x(..)
      integer(i8), allocatable :: v(:)
      select rank (x)
      rank (0)
         v = [int(x, i8)]
      rank (1)
         v = int(x, i8)
      rank (2)
         v = int(reshape(x, [size(x)]), i8)
      rank (3)
         v = int(reshape(x, [size(x)]), i8)
      rank (4)
         v = int(reshape(x, [size(x)]), i8)
      rank (5)
         v = int(reshape(x, [size(x)]), i8)
      rank default
         allocate (v(0))
      end select
   end function as_i8_from_int

   pure function as_i8_from_i8(x) result(v)
      integer(i8), intent(in) :: x(..)
      integer(i8), allocatable :: v(:)
      select rank (x)
      rank (0)
         v = [x]
      rank (1)
         v = x
      rank (2)
         v = reshape(x, [size(x)])
      rank (3)
         v = reshape(x, [size(x)])
      rank (4)
         v = reshape(x, [size(x)])
      rank (5)
         v = reshape(x, [size(x)])
      rank default
         allocate (v(0))
      end select
   end function as_i8_from_i8

   pure function as_lgc(x) result(v)
      logical, intent(in) :: x(..)
      logical, allocatable :: v(:)
      select rank (x)
      rank (0)
         v = [x]
      rank (1)
         v = x
      rank (2)
         v = reshape(x, [size(x)])
      rank (3)
         v = reshape(x, [size(x)])
      rank (4)
         v = reshape(x, [size(x)])
      rank (5)
         v = reshape(x, [size(x)])
      rank default
         allocate (v(0))
      end select
   end function as_lgc

end module funit
