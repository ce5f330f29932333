!> bind(C) interfaces to SuiteSparse UMFPACK, int/double version (`umfpack_di_*`).
!!
!! Interfaces and constants only: no logic lives here (see `umfpack_solver`).
!! The constants are those of SuiteSparse's `umfpack.h` (UMFPACK 5.x); the
!! index arrays are 0-based compressed-column (CSC) arrays of C `int`.
!! Optional C arguments (NULL allowed) are declared `type(c_ptr), value`.
!!
!! Ref: T. A. Davis, UMFPACK User Guide (SuiteSparse), sections "Primary
!!      routines" and "umfpack_get_numeric".
module umfpack_c
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr
   implicit none
   private

   public :: umfpack_di_defaults, umfpack_di_symbolic, umfpack_di_numeric, umfpack_di_solve, &
         umfpack_di_wsolve, &
             umfpack_di_free_symbolic, umfpack_di_free_numeric, umfpack_di_get_lunz, &
             umfpack_di_get_numeric

   !> Sizes of the Control and Info arrays.
   integer, parameter, public :: UMFPACK_CONTROL = 20, UMFPACK_INFO = 90

   !> Status codes (return values and Info(UMFPACK_STATUS)).
   integer(c_int), parameter, public :: UMFPACK_OK = 0
   integer(c_int), parameter, public :: UMFPACK_WARNING_singular_matrix = 1
   integer(c_int), parameter, public :: UMFPACK_WARNING_determinant_underflow = 2
   integer(c_int), parameter, public :: UMFPACK_WARNING_determinant_overflow = 3
   integer(c_int), parameter, public :: UMFPACK_ERROR_out_of_memory = -1
   integer(c_int), parameter, public :: UMFPACK_ERROR_invalid_Numeric_object = -3
   integer(c_int), parameter, public :: UMFPACK_ERROR_invalid_Symbolic_object = -4
   integer(c_int), parameter, public :: UMFPACK_ERROR_argument_missing = -5
   integer(c_int), parameter, public :: UMFPACK_ERROR_n_nonpositive = -6
   integer(c_int), parameter, public :: UMFPACK_ERROR_invalid_matrix = -8
   integer(c_int), parameter, public :: UMFPACK_ERROR_different_pattern = -11
   integer(c_int), parameter, public :: UMFPACK_ERROR_invalid_system = -13
   integer(c_int), parameter, public :: UMFPACK_ERROR_invalid_permutation = -15
   integer(c_int), parameter, public :: UMFPACK_ERROR_file_IO = -17
   integer(c_int), parameter, public :: UMFPACK_ERROR_ordering_failed = -18
   integer(c_int), parameter, public :: UMFPACK_ERROR_internal_error = -911

   !> Systems for umfpack_di_solve.
   integer(c_int), parameter, public :: UMFPACK_A = 0

   !> Control entries (0-based C indices; add 1 for the Fortran array).
   integer, parameter, public :: UMFPACK_PRL = 0, UMFPACK_STRATEGY = 5, UMFPACK_IRSTEP = 7, &
                                 UMFPACK_ORDERING = 10, UMFPACK_SCALE = 16
   real(c_double), parameter, public :: UMFPACK_STRATEGY_SYMMETRIC = 3.0_c_double

   !> Info entries (0-based C indices; add 1 for the Fortran array).
   integer, parameter, public :: UMFPACK_STATUS = 0, UMFPACK_SIZE_OF_UNIT = 3, &
                                 UMFPACK_SYMBOLIC_PEAK_MEMORY = 13, UMFPACK_SYMBOLIC_SIZE = 14, &
                                 UMFPACK_NUMERIC_SIZE = 40, UMFPACK_PEAK_MEMORY = 41, &
                                 UMFPACK_FLOPS = 42, UMFPACK_LNZ = 43, UMFPACK_UNZ = 44, &
                                 UMFPACK_RCOND = 67, UMFPACK_UMIN = 71, UMFPACK_UMAX = 72, &
                                 UMFPACK_IR_TAKEN = 80, UMFPACK_OMEGA1 = 82, UMFPACK_OMEGA2 = 83

   interface
      !> Default Control parameters.
      subroutine umfpack_di_defaults(control) bind(C, name='umfpack_di_defaults')
         import :: c_double
         real(c_double), intent(out) :: control(*)
      end subroutine umfpack_di_defaults

      !> Symbolic analysis (ordering, elimination tree) of a CSC pattern.
      !! `ax` may be C_NULL_PTR: the analysis then depends on the pattern only.
      integer(c_int) function umfpack_di_symbolic(n_row, n_col, ap, ai, ax, symbolic, control, &
                                                  info) &
         bind(C, name='umfpack_di_symbolic')
         import :: c_int, c_double, c_ptr
         integer(c_int), value :: n_row, n_col
         integer(c_int), intent(in) :: ap(*), ai(*)
         type(c_ptr), value :: ax
         type(c_ptr), intent(out) :: symbolic
         real(c_double), intent(in) :: control(*)
         real(c_double), intent(out) :: info(*)
      end function umfpack_di_symbolic

      !> Numeric LU factorization with a given symbolic object.
      integer(c_int) function umfpack_di_numeric(ap, ai, ax, symbolic, numeric, control, info) &
         bind(C, name='umfpack_di_numeric')
         import :: c_int, c_double, c_ptr
         integer(c_int), intent(in) :: ap(*), ai(*)
         real(c_double), intent(in) :: ax(*)
         type(c_ptr), value :: symbolic
         type(c_ptr), intent(out) :: numeric
         real(c_double), intent(in) :: control(*)
         real(c_double), intent(out) :: info(*)
      end function umfpack_di_numeric

      !> Solve A x = b (sys = UMFPACK_A) with the LU factors; iterative
      !! refinement uses ap, ai, ax, which must be the factored matrix.
      integer(c_int) function umfpack_di_solve(sys, ap, ai, ax, x, b, numeric, control, info) &
         bind(C, name='umfpack_di_solve')
         import :: c_int, c_double, c_ptr
         integer(c_int), value :: sys
         integer(c_int), intent(in) :: ap(*), ai(*)
         real(c_double), intent(in) :: ax(*)
         real(c_double), intent(out) :: x(*)
         real(c_double), intent(in) :: b(*)
         type(c_ptr), value :: numeric
         real(c_double), intent(in) :: control(*)
         real(c_double), intent(out) :: info(*)
      end function umfpack_di_solve

      !> umfpack_di_solve with the workspace given (no allocation inside):
      !! Wi (n) and W (n without iterative refinement, 5 n with it).
      integer(c_int) function umfpack_di_wsolve(sys, ap, ai, ax, x, b, numeric, control, info, &
                                                wi, w) &
         bind(C, name='umfpack_di_wsolve')
         import :: c_int, c_double, c_ptr
         integer(c_int), value :: sys
         integer(c_int), intent(in) :: ap(*), ai(*)
         real(c_double), intent(in) :: ax(*)
         real(c_double), intent(out) :: x(*)
         real(c_double), intent(in) :: b(*)
         type(c_ptr), value :: numeric
         real(c_double), intent(in) :: control(*)
         real(c_double), intent(out) :: info(*)
         integer(c_int), intent(out) :: wi(*)
         real(c_double), intent(out) :: w(*)
      end function umfpack_di_wsolve

      !> Free a symbolic object and set the handle to NULL.
      subroutine umfpack_di_free_symbolic(symbolic) bind(C, name='umfpack_di_free_symbolic')
         import :: c_ptr
         type(c_ptr), intent(inout) :: symbolic
      end subroutine umfpack_di_free_symbolic

      !> Free a numeric object and set the handle to NULL.
      subroutine umfpack_di_free_numeric(numeric) bind(C, name='umfpack_di_free_numeric')
         import :: c_ptr
         type(c_ptr), intent(inout) :: numeric
      end subroutine umfpack_di_free_numeric

      !> Sizes of the factors: nonzeros of L and U, and of the diagonal of U.
      integer(c_int) function umfpack_di_get_lunz(lnz, unz, n_row, n_col, nz_udiag, numeric) &
         bind(C, name='umfpack_di_get_lunz')
         import :: c_int, c_ptr
         integer(c_int), intent(out) :: lnz, unz, n_row, n_col, nz_udiag
         type(c_ptr), value :: numeric
      end function umfpack_di_get_lunz

      !> Parts of the factors: P R A Q = L U.  Every array is optional (NULL);
      !! here it serves to read the diagonal of U (dx), the permutations p
      !! and q (0-based) and the row scale factors rs.
      integer(c_int) function umfpack_di_get_numeric(lp, lj, lx, up, ui, ux, p, q, dx, do_recip, &
                                                     rs, numeric) &
         bind(C, name='umfpack_di_get_numeric')
         import :: c_int, c_ptr
         type(c_ptr), value :: lp, lj, lx, up, ui, ux, p, q, dx
         integer(c_int), intent(out) :: do_recip
         type(c_ptr), value :: rs, numeric
      end function umfpack_di_get_numeric
   end interface
end module umfpack_c
