!> Dense reference solver: full symmetric storage, LAPACK Cholesky.
!!
!! The upper triangle of K is assembled into a full n x n array and factorized
!! by LAPACK `dpotrf` (K = U^T U) into a separate array, so that the assembled
!! values survive for diagnostics; `dpotrs` solves with the factor.  Meant as
!! the reference of the tests and for small systems (memory 8 n^2 bytes per
!! array, time n^3/3): it refuses more than `max_neq` equations.
!!
!! The pivots are reported as those of LDL^T, d_i = u_ii^2, and checked with
!! the same relative threshold as the skyline solver, so that both stop at
!! the same equation for a singular or indefinite matrix.
!! Ref: Golub & Van Loan, Matrix Computations (4th ed.), sec. 4.2 (Cholesky);
!!      LAPACK Users' Guide, DPOTRF / DPOTRS.
module dense_solver
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp, i8
   use errors, only: status_t, fatal_internal, STAT_SINGULAR, STAT_SOLVER
   use linear_solver, only: linear_solver_t, solver_stats_t, ST_EMPTY, ST_ASSEMBLING, &
         ST_FACTORED, ST_FAILED
   use lapack_interfaces, only: dpotrf, dpotrs, dtrtrs
   implicit none
   private

   public :: dense_solver_t


   !> Dense Cholesky solver with the `linear_solver_t` life cycle.
   type, extends(linear_solver_t) :: dense_solver_t
      !> Relative pivot threshold, as for the skyline solver: a pivot
      !! d_i = u_ii^2 <= pivot_tol * |k_ii| is reported as singular.
      real(dp) :: pivot_tol = 1.0e-12_dp
      !> Largest system accepted by `analyse` (three n x n arrays: 2.4 GB at 1e4).
      integer :: max_neq = 10000
      real(dp), allocatable, private :: k(:, :)     ! assembled matrix, upper triangle used
      real(dp), allocatable, private :: f(:, :)     ! Cholesky factor U (upper)
      real(dp), allocatable, private :: base(:, :)  ! stored copy of K_AB
   contains
      procedure :: analyse => dense_analyse
      procedure :: zero => dense_zero
      procedure :: add_element => dense_add_element
      procedure :: store_base => dense_store_base
      procedure :: restore_base => dense_restore_base
      procedure :: factorize => dense_factorize
      procedure :: solve => dense_solve
      procedure :: free => dense_free
      procedure :: name => dense_name
   end type dense_solver_t

contains

   !> Allocate the full matrix; the graph is not needed (every entry is stored).
   subroutine dense_analyse(this, neq, xadj, adjncy, status)
      class(dense_solver_t), intent(inout) :: this
      integer, intent(in) :: neq          !! number of equations
      integer, intent(in) :: xadj(:)      !! (neq+1) 1-based CSR row pointers (checked only)
      integer, intent(in) :: adjncy(:)    !! coupled equations of each row (checked only)
      type(status_t), intent(inout) :: status
      integer :: ierr
      character(len=160) :: buf

      call this%free()
      ! Every entry is stored, so the graph is only checked for consistency.
      if (neq > 0) then
         if (size(xadj) < neq + 1) then
            call status%set(STAT_SOLVER, 'dense solver: invalid equation graph (xadj too short)')
            return
         end if
         if (any(adjncy(1:min(size(adjncy), xadj(neq + 1) - 1)) < 1) .or. &
             any(adjncy(1:min(size(adjncy), xadj(neq + 1) - 1)) > neq)) then
            call status%set(STAT_SOLVER, &
                            'dense solver: invalid equation graph (equation out of range)')
            return
         end if
      end if
      if (neq < 0 .or. neq > this%max_neq) then
         write (buf, '(a,i0,a,i0,a)') 'dense solver: cannot take ', neq, &
            ' equations (at most ', this%max_neq, '); use the skyline solver'
         call status%set(STAT_SOLVER, trim(buf))
         return
      end if
      allocate (this%k(neq, neq), this%f(neq, neq), stat=ierr)
      if (ierr /= 0) then
         write (buf, '(a,i0,a)') 'dense solver: cannot allocate two ', neq, '^2 arrays'
         call status%set(STAT_SOLVER, trim(buf))
         call this%free()
         return
      end if
      this%k = 0.0_dp
      this%f = 0.0_dp
      this%neq = neq
      this%state = ST_ASSEMBLING
      this%stats%neq = neq
      this%stats%nnz_matrix = int(neq, i8)*int(neq + 1, i8)/2
      this%stats%nnz_factor = this%stats%nnz_matrix
      call update_memory(this)
   end subroutine dense_analyse

   !> Memory held by the full arrays.
   subroutine update_memory(this)
      class(dense_solver_t), intent(inout) :: this
      integer(i8) :: m
      m = 0
      if (allocated(this%k)) m = m + storage_size(this%k, i8)/8*size(this%k, kind=i8)
      if (allocated(this%f)) m = m + storage_size(this%f, i8)/8*size(this%f, kind=i8)
      if (allocated(this%base)) m = m + storage_size(this%base, i8)/8*size(this%base, kind=i8)
      this%stats%memory_bytes = m
   end subroutine update_memory

   !> Set every assembled value to zero.
   subroutine dense_zero(this)
      class(dense_solver_t), intent(inout) :: this
      if (this%state == ST_EMPTY) then
         call fatal_internal('dense solver: zero called before analyse', 'dense_solver.f90', &
                             __LINE__)
      end if
      this%k = 0.0_dp
      this%n_outside = 0
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine dense_zero

   !> Scatter a symmetric element matrix into the upper triangle.
   !!
   !! Same rule as the skyline solver: ke(a, b) goes to K(ieq(a), ieq(b)) when
   !! ieq(a) <= ieq(b), so tied dofs sum correctly onto the diagonal; dofs with
   !! ieq <= 0 are skipped; a nonzero entry with ieq > neq is reported by the
   !! next `factorize`.
   subroutine dense_add_element(this, ieq, ke)
      class(dense_solver_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)       !! global equation of each element dof
      real(dp), intent(in) :: ke(:, :)    !! element matrix, size(ieq) square, symmetric
      integer :: ia, ib, i, j, nd

      call this%check_element(ieq, ke, 'dense_solver.f90', __LINE__)
      nd = size(ieq)
      do ib = 1, nd
         j = ieq(ib)
         if (j <= 0) cycle
         do ia = 1, nd
            i = ieq(ia)
            if (i <= 0 .or. i > j) cycle
            if (j > this%neq) then
               if (.not. (abs(ke(ia, ib)) <= 0.0_dp)) this%n_outside = this%n_outside + 1
               cycle
            end if
            this%k(i, j) = this%k(i, j) + ke(ia, ib)
         end do
      end do
   end subroutine dense_add_element

   !> Keep a copy of the assembled values (K_AB).
   subroutine dense_store_base(this)
      class(dense_solver_t), intent(inout) :: this
      if (this%state /= ST_ASSEMBLING) call fatal_internal( &
         'dense solver: store_base needs assembled values (call it before factorize)', &
         'dense_solver.f90', __LINE__)
      this%base = this%k
      this%base_outside = this%n_outside
      call update_memory(this)
   end subroutine dense_store_base

   !> Put back the values kept by `store_base`.
   subroutine dense_restore_base(this)
      class(dense_solver_t), intent(inout) :: this
      if (.not. allocated(this%base) .or. this%state == ST_EMPTY) call fatal_internal( &
         'dense solver: restore_base without store_base', 'dense_solver.f90', __LINE__)
      this%k(:, :) = this%base(:, :)
      this%n_outside = this%base_outside
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine dense_restore_base

   !> Cholesky factorization by DPOTRF with the skyline solver's pivot check.
   !!
   !! A failure of DPOTRF at equation i (info = i) and a pivot u_ii^2 <=
   !! pivot_tol * |k_ii| both give STAT_SINGULAR with `failed_equation() = i`
   !! (the first such i).  For the message the pivot that DPOTRF rejected is
   !! recomputed from the leading (i-1) block: d_i = k_ii - |U11^{-T} k_1:i-1,i|^2.
   !! Ref: Golub & Van Loan (4th ed.), sec. 4.2.
   subroutine dense_factorize(this, status)
      class(dense_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status  !! set only on failure
      integer :: info, i, n, nneg
      real(dp) :: di, ratio
      character(len=120) :: buf

      select case (this%state)
      case (ST_EMPTY)
         call status%set(STAT_SOLVER, 'dense solver: factorize called before analyse')
         return
      case (ST_FACTORED, ST_FAILED)
         call status%set(STAT_SOLVER, 'dense solver: factorize called twice on the same '// &
                         'values (call restore_base or zero and assemble again)')
         return
      end select
      if (this%n_outside > 0) then
         write (buf, '(a,i0,a)') 'dense solver: ', this%n_outside, &
            ' assembled entries have equation numbers beyond neq'
         call fail(this, status, STAT_SOLVER, trim(buf), 0)
         return
      end if
      n = this%neq
      if (.not. all(ieee_is_finite(this%k))) then
         call fail(this, status, STAT_SOLVER, &
                   'dense solver: the assembled matrix holds NaN or Inf', 0)
         return
      end if
      this%f(:, :) = this%k(:, :)
      info = 0
      if (n > 0) call dpotrf('U', n, this%f, n, info)
      if (info < 0) then
         write (buf, '(a,i0)') 'dense solver: DPOTRF rejected argument ', -info
         call fail(this, status, STAT_SOLVER, trim(buf), 0)
         return
      end if

      ! Pivots d_i = u_ii^2 of the part DPOTRF completed, checked in order.
      ratio = 1.0_dp
      nneg = 0
      do i = 1, merge(info - 1, n, info > 0)
         di = this%f(i, i)**2
         ratio = min(ratio, pivot_ratio(di, this%k(i, i)))
         if (.not. (di > this%pivot_tol*abs(this%k(i, i)))) then
            this%stats%negative_pivots = nneg
            this%stats%pivot_ratio = ratio
            call fail(this, status, STAT_SINGULAR, pivot_message(i, di, this%k(i, i)), i)
            return
         end if
      end do
      if (info > 0) then
         di = rejected_pivot(this%k, info)
         if (di < 0.0_dp) nneg = nneg + 1
         this%stats%negative_pivots = nneg
         this%stats%pivot_ratio = min(ratio, pivot_ratio(di, this%k(info, info)))
         call fail(this, status, STAT_SINGULAR, pivot_message(info, di, this%k(info, info)), info)
         return
      end if
      this%stats%negative_pivots = 0
      this%stats%pivot_ratio = ratio
      this%stats%factorizations = this%stats%factorizations + 1
      this%bad_eq = 0
      this%state = ST_FACTORED
   end subroutine dense_factorize

   !> |d| / |k_ii|, zero when the diagonal is zero.
   pure real(dp) function pivot_ratio(d, kii)
      real(dp), intent(in) :: d     !! pivot
      real(dp), intent(in) :: kii   !! diagonal before reduction
      if (abs(kii) > 0.0_dp) then
         pivot_ratio = abs(d)/abs(kii)
      else
         pivot_ratio = 0.0_dp
      end if
   end function pivot_ratio

   !> Pivot d_i of LDL^T at the equation where DPOTRF stopped.
   !!
   !! The leading minor of order i-1 is positive definite, so its factor
   !! exists: d_i = k_ii - y^T y with U11^T y = k(1:i-1, i).  O(i^3), paid
   !! only on failure.
   function rejected_pivot(k, i) result(d)
      real(dp), intent(in) :: k(:, :)   !! assembled matrix (upper triangle)
      integer, intent(in) :: i          !! equation at which DPOTRF stopped
      real(dp) :: d
      real(dp), allocatable :: w(:, :), y(:, :)
      integer :: m, info

      m = i - 1
      d = k(i, i)
      if (m == 0) return
      allocate (w(m, m), y(m, 1))
      w(:, :) = k(1:m, 1:m)
      y(:, 1) = k(1:m, i)
      call dpotrf('U', m, w, m, info)
      if (info /= 0) return
      call dtrtrs('U', 'T', 'N', m, 1, w, m, y, m, info)
      if (info /= 0) return
      d = k(i, i) - dot_product(y(:, 1), y(:, 1))
   end function rejected_pivot

   !> Record a failed factorization.
   subroutine fail(this, status, code, msg, eq)
      class(dense_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer, intent(in) :: code         !! status code to report
      character(len=*), intent(in) :: msg !! full message
      integer, intent(in) :: eq           !! failed equation, 0 if none
      this%bad_eq = eq
      this%fail_msg = msg
      this%state = ST_FAILED
      call status%set(code, msg)
   end subroutine fail

   !> Solve K x = b by DPOTRS; b is overwritten with x, and left unchanged
   !! (status STAT_SOLVER) when there is no valid factorization.
   subroutine dense_solve(this, b, status)
      class(dense_solver_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)          !! (neq) right-hand side in, solution out
      type(status_t), intent(inout) :: status  !! set only on failure
      integer :: info
      character(len=120) :: buf

      if (.not. this%ready_to_solve(size(b), status)) return
      if (this%neq == 0) return
      call dpotrs('U', this%neq, 1, this%f, this%neq, b, this%neq, info)
      if (info /= 0) then
         write (buf, '(a,i0)') 'dense solver: DPOTRS failed, info = ', info
         call status%set(STAT_SOLVER, trim(buf))
         return
      end if
      this%stats%solves = this%stats%solves + 1
   end subroutine dense_solve

   !> Release all storage; the solver is as new (statistics reset).
   subroutine dense_free(this)
      class(dense_solver_t), intent(inout) :: this
      if (allocated(this%k)) deallocate (this%k)
      if (allocated(this%f)) deallocate (this%f)
      if (allocated(this%base)) deallocate (this%base)
      call this%reset_common()
   end subroutine dense_free

   !> Name of the solver as given in the deck.
   function dense_name(this) result(s)
      class(dense_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      associate (unused => this)   ! the name is the same for every instance
      end associate
      s = 'dense'
   end function dense_name

   !> Message of a zero or negative pivot, naming the equation.
   pure function pivot_message(j, dj, kjj) result(msg)
      integer, intent(in) :: j        !! equation
      real(dp), intent(in) :: dj      !! pivot d_j
      real(dp), intent(in) :: kjj     !! diagonal k_jj before reduction
      character(len=:), allocatable :: msg
      character(len=24) :: sj, sd, sk
      write (sj, '(i0)') j
      write (sd, '(es12.5)') dj
      write (sk, '(es12.5)') kjj
      msg = 'singular or unrestrained model: zero or negative pivot at equation '// &
            trim(sj)//' (pivot = '//trim(adjustl(sd))//', diagonal = '//trim(adjustl(sk))//')'
   end function pivot_message
end module dense_solver
