!> Explicit interfaces of the BLAS and LAPACK routines the dense solvers call
!! (reference BLAS/LAPACK or OpenBLAS, whichever the build links), written
!! once so that every caller is checked against the same argument lists.
!!
!! Ref: E. Anderson et al., LAPACK Users' Guide, 3rd ed., SIAM 1999
!!      (DGETRF, DGETRS, DPOTRF, DPOTRI, DPOTRS, DTRTRS, DSYEV); BLAS level 2
!!      and 3 (DGEMV, DSYMV, DTRSV, DGEMM).  One right-hand side is solved
!!      with two DTRSV, not DPOTRS: OpenBLAS's DTRSM behind DPOTRS packs its
!!      operands as for many columns (measured here at n = 1 202: 0.68 ms
!!      against 0.15 ms).
module lapack_interfaces
   use kinds, only: dp
   implicit none
   private
   public :: dgemm, dgemv, dsymv, dtrsv, dtrsm, dsyrk, dgetrf, dgetrs, dpotrf, dpotri, dpotrs, &
         dtrtrs, dsyev

   interface
      subroutine dgemm(transa, transb, m, n, k, alpha, a, lda, b, ldb, beta, c, ldc)
         import :: dp
         character(len=1), intent(in) :: transa, transb
         integer, intent(in) :: m, n, k, lda, ldb, ldc
         real(dp), intent(in) :: alpha, beta, a(lda, *), b(ldb, *)
         real(dp), intent(inout) :: c(ldc, *)
      end subroutine dgemm
      subroutine dgemv(trans, m, n, alpha, a, lda, x, incx, beta, y, incy)
         import :: dp
         character(len=1), intent(in) :: trans
         integer, intent(in) :: m, n, lda, incx, incy
         real(dp), intent(in) :: alpha, beta, a(lda, *), x(*)
         real(dp), intent(inout) :: y(*)
      end subroutine dgemv
      subroutine dsymv(uplo, n, alpha, a, lda, x, incx, beta, y, incy)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda, incx, incy
         real(dp), intent(in) :: alpha, beta, a(lda, *), x(*)
         real(dp), intent(inout) :: y(*)
      end subroutine dsymv
      subroutine dtrsv(uplo, trans, diag, n, a, lda, x, incx)
         import :: dp
         character(len=1), intent(in) :: uplo, trans, diag
         integer, intent(in) :: n, lda, incx
         real(dp), intent(in) :: a(lda, *)
         real(dp), intent(inout) :: x(*)
      end subroutine dtrsv
      subroutine dtrsm(side, uplo, transa, diag, m, n, alpha, a, lda, b, ldb)
         import :: dp
         character(len=1), intent(in) :: side, uplo, transa, diag
         integer, intent(in) :: m, n, lda, ldb
         real(dp), intent(in) :: alpha, a(lda, *)
         real(dp), intent(inout) :: b(ldb, *)
      end subroutine dtrsm
      subroutine dsyrk(uplo, trans, n, k, alpha, a, lda, beta, c, ldc)
         import :: dp
         character(len=1), intent(in) :: uplo, trans
         integer, intent(in) :: n, k, lda, ldc
         real(dp), intent(in) :: alpha, beta, a(lda, *)
         real(dp), intent(inout) :: c(ldc, *)
      end subroutine dsyrk
      subroutine dgetrf(m, n, a, lda, ipiv, info)
         import :: dp
         integer, intent(in) :: m, n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: ipiv(*), info
      end subroutine dgetrf
      subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: trans
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         integer, intent(in) :: ipiv(*)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dgetrs
      subroutine dpotrf(uplo, n, a, lda, info)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: info
      end subroutine dpotrf
      subroutine dpotri(uplo, n, a, lda, info)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, lda
         real(dp), intent(inout) :: a(lda, *)
         integer, intent(out) :: info
      end subroutine dpotri
      subroutine dpotrs(uplo, n, nrhs, a, lda, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: uplo
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dpotrs
      subroutine dtrtrs(uplo, trans, diag, n, nrhs, a, lda, b, ldb, info)
         import :: dp
         character(len=1), intent(in) :: uplo, trans, diag
         integer, intent(in) :: n, nrhs, lda, ldb
         real(dp), intent(in) :: a(lda, *)
         real(dp), intent(inout) :: b(ldb, *)
         integer, intent(out) :: info
      end subroutine dtrtrs
      subroutine dsyev(jobz, uplo, n, a, lda, w, work, lwork, info)
         import :: dp
         character(len=1), intent(in) :: jobz, uplo
         integer, intent(in) :: n, lda, lwork
         real(dp), intent(inout) :: a(lda, *)
         real(dp), intent(out) :: w(*), work(*)
         integer, intent(out) :: info
      end subroutine dsyev
   end interface
end module lapack_interfaces
