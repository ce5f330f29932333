!> Skyline (profile) solver: symmetric LDL^T by the active-column method.
!!
!! Storage.  Only the upper triangle is kept, column by column, each column
!! from its first coupled row `top(j)` down to the diagonal, which comes last.
!! The columns are packed one after the other in `a(:)`; `jdiag(j)` is the
!! address of the diagonal of column j (`jdiag(0) = 0`), so that column j
!! occupies `a(jdiag(j-1)+1 : jdiag(j))` and entry (i, j), top(j) <= i <= j,
!! sits at `jdiag(j) - (j - i)`.  This is Bathe's MAXA scheme with each column
!! stored top-down, so that every inner loop of the factorization and of the
!! solve is a dot product or an axpy over two contiguous segments.
!!
!! Factorization.  K = L D L^T, overwriting column j of the profile with row j
!! of L (unit diagonal not stored) and the diagonal with d_j.  Column j is
!! reduced when it becomes active (Crout order), using only columns < j:
!!
!!     g_ij = k_ij - sum_{r=max(top_i,top_j)}^{i-1} l_ri g_rj,  top_j < i < j
!!     l_ij = g_ij / d_i,  d_j = k_jj - sum_{r=top_j}^{j-1} l_rj g_rj
!!
!! Ref: Bathe, Finite Element Procedures (1996), sec. 8.2.3, the active-column
!!      solution and its subroutine COLSOL; Hinton & Owen's profile solver.
!!
!! Cost: O(sum_j h_j^2) ~ O(n b^2) operations and O(n b) memory for n
!! equations and a mean column height b; the profile pointers are 64-bit
!! because a profile can exceed 2^31 entries.
module skyline_solver
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp, i8
   use errors, only: status_t, fatal_internal, STAT_SINGULAR, STAT_SOLVER
   use graph, only: column_tops
   use linear_solver, only: linear_solver_t, solver_stats_t, ST_EMPTY, ST_ASSEMBLING, &
         ST_FACTORED, ST_FAILED
   implicit none
   private

   public :: skyline_solver_t

   !> Life-cycle states (private): what the values in `a` currently are.

   !> Profile LDL^T solver of a symmetric positive definite system.
   type, extends(linear_solver_t) :: skyline_solver_t
      !> Relative pivot threshold: a pivot d_j <= pivot_tol * |k_jj| stops the
      !! factorization.  A rigid-body mode leaves d_j at round-off level,
      !! |d_j| ~ (a few units of 1e-16) * |k_jj|; 1e-12 leaves four orders of
      !! magnitude for round-off growth along long chains of eliminations, and
      !! still lets through every genuinely positive pivot of a restrained
      !! model, including penalty-like springs up to 1e11 times the stiffness
      !! of the body they touch.
      real(dp) :: pivot_tol = 1.0e-12_dp
      integer, allocatable, private :: top(:)        ! (neq) first coupled row of column j
      integer(i8), allocatable, private :: jdiag(:)  ! (0:neq) address of diagonal j in a
      real(dp), allocatable, private :: a(:)         ! profile values, matrix or factors
      real(dp), allocatable, private :: base(:)      ! stored copy of K_AB
   contains
      procedure :: analyse => skyline_analyse
      procedure :: zero => skyline_zero
      procedure :: add_element => skyline_add_element
      procedure :: store_base => skyline_store_base
      procedure :: restore_base => skyline_restore_base
      procedure :: factorize => skyline_factorize
      procedure :: solve => skyline_solve
      procedure :: free => skyline_free
      procedure :: name => skyline_name
      procedure :: profile_length => skyline_profile_length
      procedure :: mean_column_height => skyline_mean_column_height
      procedure :: max_column_height => skyline_max_column_height
   end type skyline_solver_t

contains

   !> Symbolic set-up: column heights and diagonal pointers from the graph.
   !!
   !! Allocates the profile (set to zero), so that assembly can start at once.
   !! O(neq + nnz) work.  Sets STAT_SOLVER for an invalid graph or when the
   !! profile cannot be allocated.
   subroutine skyline_analyse(this, neq, xadj, adjncy, status)
      class(skyline_solver_t), intent(inout) :: this
      integer, intent(in) :: neq          !! number of equations
      integer, intent(in) :: xadj(:)      !! (neq+1) 1-based CSR row pointers of the graph
      integer, intent(in) :: adjncy(:)    !! columns coupled to each row, diagonal included
      type(status_t), intent(inout) :: status
      integer :: ierr, j
      character(len=:), allocatable :: msg
      character(len=120) :: buf

      call this%free()
      allocate (this%top(max(neq, 0)))
      call column_tops(neq, xadj, adjncy, this%top, ierr, msg)
      if (ierr /= 0) then
         deallocate (this%top)
         call status%set(STAT_SOLVER, msg)
         return
      end if
      allocate (this%jdiag(0:neq))
      this%jdiag(0) = 0
      do j = 1, neq
         this%jdiag(j) = this%jdiag(j - 1) + int(j - this%top(j) + 1, i8)
      end do
      allocate (this%a(this%jdiag(neq)), stat=ierr)
      if (ierr /= 0) then
         write (buf, '(a,i0,a)') 'skyline solver: cannot allocate a profile of ', &
            this%jdiag(neq), ' entries'
         call status%set(STAT_SOLVER, trim(buf))
         call this%free()
         return
      end if
      this%a = 0.0_dp
      this%neq = neq
      this%state = ST_ASSEMBLING
      this%stats%neq = neq
      this%stats%nnz_matrix = this%jdiag(neq)
      this%stats%nnz_factor = this%jdiag(neq)
      call update_memory(this)
   end subroutine skyline_analyse

   !> Memory held: the profile, its stored copy, the pointers and the tops.
   subroutine update_memory(this)
      class(skyline_solver_t), intent(inout) :: this
      integer(i8) :: m
      m = 0
      if (allocated(this%a)) m = m + storage_size(this%a, i8)/8*size(this%a, kind=i8)
      if (allocated(this%base)) m = m + storage_size(this%base, i8)/8*size(this%base, kind=i8)
      if (allocated(this%jdiag)) m = m + storage_size(this%jdiag, i8)/8*size(this%jdiag, kind=i8)
      if (allocated(this%top)) m = m + storage_size(this%top, i8)/8*size(this%top, kind=i8)
      this%stats%memory_bytes = m
   end subroutine update_memory

   !> Set every stored value to zero, ready for a fresh assembly.
   subroutine skyline_zero(this)
      class(skyline_solver_t), intent(inout) :: this
      if (this%state == ST_EMPTY) then
         call fatal_internal('skyline solver: zero called before analyse', 'skyline_solver.f90', &
                             __LINE__)
      end if
      this%a = 0.0_dp
      this%n_outside = 0
      this%first_outside = 0
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine skyline_zero

   !> Scatter a symmetric element matrix into the profile (ADDBAN).
   !!
   !! Entry ke(a, b) goes to K(ieq(a), ieq(b)) when ieq(a) <= ieq(b), which
   !! builds the upper triangle of K = T^T ke T for the boolean map T even
   !! when several element dofs share one equation (ties): both ke(a, b) and
   !! ke(b, a) of tied dofs a, b then land on the diagonal, as they must.
   !! Dofs with ieq <= 0 (restrained) are skipped.  A nonzero entry outside
   !! the profile given to `analyse` (or ieq > neq) is counted and reported
   !! by the next `factorize`; it is never dropped silently.
   !! Ref: Bathe (1996), the COLSOL storage scheme; Hinton & Owen's profile assembly.
   subroutine skyline_add_element(this, ieq, ke)
      class(skyline_solver_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)       !! global equation of each element dof
      real(dp), intent(in) :: ke(:, :)    !! element matrix, size(ieq) square, symmetric
      integer :: ia, ib, i, j, nd
      integer(i8) :: p

      call this%check_element(ieq, ke, 'skyline_solver.f90', __LINE__)
      nd = size(ieq)
      do ib = 1, nd
         j = ieq(ib)
         if (j <= 0) cycle
         do ia = 1, nd
            i = ieq(ia)
            if (i <= 0 .or. i > j) cycle
            if (j <= this%neq) then
               if (i >= this%top(j)) then
                  p = this%jdiag(j) - (j - i)
                  this%a(p) = this%a(p) + ke(ia, ib)
                  cycle
               end if
            end if
            ! An exact zero outside the profile changes nothing; anything else
            ! (NaN included) means the graph given to analyse was incomplete.
            if (.not. (abs(ke(ia, ib)) <= 0.0_dp)) call note_outside(this, i, j)
         end do
      end do
   end subroutine skyline_add_element

   !> Remember one assembled entry that the profile cannot hold.
   subroutine note_outside(this, i, j)
      class(skyline_solver_t), intent(inout) :: this
      integer, intent(in) :: i, j   !! row and column of the entry
      if (this%n_outside == 0) this%first_outside = [i, j]
      this%n_outside = this%n_outside + 1
   end subroutine note_outside

   !> Keep a copy of the assembled values (K_AB) for `restore_base`.
   subroutine skyline_store_base(this)
      class(skyline_solver_t), intent(inout) :: this
      if (this%state /= ST_ASSEMBLING) call fatal_internal( &
         'skyline solver: store_base needs assembled values (call it before factorize)', &
         'skyline_solver.f90', __LINE__)
      this%base = this%a
      this%base_outside = this%n_outside
      this%base_first_outside = this%first_outside
      call update_memory(this)
   end subroutine skyline_store_base

   !> Put back the values kept by `store_base`, discarding springs and factors.
   subroutine skyline_restore_base(this)
      class(skyline_solver_t), intent(inout) :: this
      if (.not. allocated(this%base) .or. this%state == ST_EMPTY) call fatal_internal( &
         'skyline solver: restore_base without store_base', 'skyline_solver.f90', __LINE__)
      this%a(:) = this%base(:)
      this%n_outside = this%base_outside
      this%first_outside = this%base_first_outside
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine skyline_restore_base

   !> In-place LDL^T factorization by the active-column method (COLSOL).
   !!
   !! Stops at the first pivot d_j <= pivot_tol * |k_jj| (zero, round-off or
   !! negative: a singular, unrestrained or indefinite matrix) with
   !! STAT_SINGULAR and `failed_equation() = j`, and at a non-finite pivot
   !! with STAT_SOLVER.  Records the pivot statistics in `this%stats`.
   !! Ref: Bathe (1996), sec. 8.2.3, COLSOL with KKK = 1 (triangularization).
   subroutine skyline_factorize(this, status)
      class(skyline_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status  !! set only on failure
      integer :: i, j, m, tj, r, nneg
      integer(i8) :: pdj, pi, pj, p
      real(dp) :: kjj, dj, g, l, ratio
      character(len=200) :: buf

      select case (this%state)
      case (ST_EMPTY)
         call status%set(STAT_SOLVER, 'skyline solver: factorize called before analyse')
         return
      case (ST_FACTORED, ST_FAILED)
         call status%set(STAT_SOLVER, 'skyline solver: factorize called twice on the same '// &
                         'values (call restore_base or zero and assemble again)')
         return
      end select
      if (this%n_outside > 0) then
         write (buf, '(a,i0,a,i0,a,i0,a)') 'skyline solver: ', this%n_outside, &
            ' assembled entries lie outside the profile given to analyse (first at row ', &
            this%first_outside(1), ', column ', this%first_outside(2), ')'
         call fail(this, status, STAT_SOLVER, trim(buf), 0)
         return
      end if

      associate (a => this%a, top => this%top, jdiag => this%jdiag)
         ratio = 1.0_dp
         nneg = 0
         do j = 1, this%neq
            tj = top(j)
            pdj = jdiag(j)
            kjj = a(pdj)
            ! g_ij for the active column: dot product of column i of L
            ! (rows m..i-1) with the not yet scaled column j (rows m..i-1).
            do i = tj + 1, j - 1
               m = max(top(i), tj)
               if (m >= i) cycle
               pi = jdiag(i) - (i - m)
               pj = pdj - (j - m)
               p = pdj - (j - i)
               a(p) = a(p) - dot(a(pi:jdiag(i) - 1), a(pj:p - 1))
            end do
            ! l_rj = g_rj / d_r and the pivot d_j.
            dj = kjj
            do r = tj, j - 1
               p = pdj - (j - r)
               g = a(p)
               l = g/a(jdiag(r))
               a(p) = l
               dj = dj - l*g
            end do
            a(pdj) = dj
            if (.not. (ieee_is_finite(dj) .and. ieee_is_finite(kjj))) then
               this%stats%negative_pivots = nneg
               this%stats%pivot_ratio = ratio
               write (buf, '(a,i0,a)') 'skyline solver: non-finite pivot at equation ', j, &
                  ' (the assembled matrix holds NaN or Inf)'
               call fail(this, status, STAT_SOLVER, trim(buf), j)
               return
            end if
            if (dj < 0.0_dp) nneg = nneg + 1
            if (abs(kjj) > 0.0_dp) then
               ratio = min(ratio, abs(dj)/abs(kjj))
            else
               ratio = 0.0_dp
            end if
            if (.not. (dj > this%pivot_tol*abs(kjj))) then
               this%stats%negative_pivots = nneg
               this%stats%pivot_ratio = ratio
               call fail(this, status, STAT_SINGULAR, pivot_message(j, dj, kjj), j)
               return
            end if
         end do
      end associate
      this%stats%negative_pivots = nneg
      this%stats%pivot_ratio = ratio
      this%stats%factorizations = this%stats%factorizations + 1
      this%bad_eq = 0
      this%state = ST_FACTORED
   end subroutine skyline_factorize

   !> Record a failed factorization.
   subroutine fail(this, status, code, msg, eq)
      class(skyline_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer, intent(in) :: code         !! status code to report
      character(len=*), intent(in) :: msg !! full message
      integer, intent(in) :: eq           !! failed equation, 0 if none
      this%bad_eq = eq
      this%fail_msg = msg
      this%state = ST_FAILED
      call status%set(code, msg)
   end subroutine fail

   !> Solve K x = b with the factors: forward reduction, diagonal scaling,
   !! back substitution.  b is overwritten with x; on any error b is left
   !! unchanged and the status is set (STAT_SOLVER).
   !! Ref: Bathe (1996), sec. 8.2.3, COLSOL with KKK = 2 (reduction and back-substitution).
   subroutine skyline_solve(this, b, status)
      class(skyline_solver_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)          !! (neq) right-hand side in, solution out
      type(status_t), intent(inout) :: status  !! set only on failure

      if (.not. this%ready_to_solve(size(b), status)) return
      call ldlt_solve(this%neq, this%a, this%top, this%jdiag, b)
      this%stats%solves = this%stats%solves + 1
   end subroutine skyline_solve

   !> Forward reduction, diagonal scaling and back substitution with the
   !! profile factors (the kernel of `solve`; x is explicit-shape, hence
   !! contiguous, so that the column segments are plain dot products and axpys).
   !! Ref: Bathe (1996), sec. 8.2.3, COLSOL with KKK = 2.
   pure subroutine ldlt_solve(n, a, top, jdiag, x)
      integer, intent(in) :: n                 !! number of equations
      real(dp), intent(in), contiguous :: a(:)  !! profile holding L (off-diagonal) and D
      integer, intent(in) :: top(:)             !! (n) first row of each column
      integer(i8), intent(in) :: jdiag(0:)      !! (0:n) diagonal addresses
      real(dp), intent(inout) :: x(n)           !! right-hand side in, solution out
      integer :: j, r, tj
      integer(i8) :: pdj, p0
      real(dp) :: xj

      ! L y = b: column j of the profile holds row j of L.
      do j = 2, n
         tj = top(j)
         if (tj < j) then
            pdj = jdiag(j)
            p0 = pdj - (j - tj)
            x(j) = x(j) - dot(a(p0:pdj - 1), x(tj:j - 1))
         end if
      end do
      ! D z = y
      do j = 1, n
         x(j) = x(j)/a(jdiag(j))
      end do
      ! L^T x = z, column by column (axpy over the column segment).
      do j = n, 2, -1
         tj = top(j)
         xj = x(j)
         p0 = jdiag(j) - (j - tj) - tj
         do r = tj, j - 1
            x(r) = x(r) - a(p0 + r)*xj
         end do
      end do
   end subroutine ldlt_solve

   !> Release all storage; the solver is as new (statistics reset).
   subroutine skyline_free(this)
      class(skyline_solver_t), intent(inout) :: this
      if (allocated(this%top)) deallocate (this%top)
      if (allocated(this%jdiag)) deallocate (this%jdiag)
      if (allocated(this%a)) deallocate (this%a)
      if (allocated(this%base)) deallocate (this%base)
      call this%reset_common()
   end subroutine skyline_free

   !> Name of the solver as given in the deck.
   function skyline_name(this) result(s)
      class(skyline_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      associate (unused => this)   ! the name is the same for every instance
      end associate
      s = 'skyline'
   end function skyline_name


   !> Number of stored entries of the profile: sum_j (h_j + 1).
   pure function skyline_profile_length(this) result(nprof)
      class(skyline_solver_t), intent(in) :: this
      integer(i8) :: nprof
      nprof = 0
      if (allocated(this%jdiag)) nprof = this%jdiag(this%neq)
   end function skyline_profile_length

   !> Mean column height, h_j = j - top_j (entries above the diagonal).
   pure function skyline_mean_column_height(this) result(h)
      class(skyline_solver_t), intent(in) :: this
      real(dp) :: h
      h = 0.0_dp
      if (this%neq > 0 .and. allocated(this%jdiag)) then
         h = real(this%jdiag(this%neq) - this%neq, dp)/real(this%neq, dp)
      end if
   end function skyline_mean_column_height

   !> Largest column height (the half-bandwidth of the profile).
   pure integer function skyline_max_column_height(this) result(h)
      class(skyline_solver_t), intent(in) :: this
      integer :: j
      h = 0
      if (.not. allocated(this%top)) return
      do j = 1, this%neq
         h = max(h, j - this%top(j))
      end do
   end function skyline_max_column_height

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

   !> Dot product of two contiguous segments.
   !!
   !! Eight independent partial sums: at -O2 they keep several multiply-adds
   !! in flight, at -O3 -march=native the compiler packs them into SIMD
   !! registers (measured on a profile of mean column height 400: about 2.5x
   !! faster than `dot_product` at -O2 and 3.5x at -O3 -march=native).
   pure function dot(x, y) result(s)
      real(dp), intent(in), contiguous :: x(:)
      real(dp), intent(in), contiguous :: y(:)
      real(dp) :: s
      real(dp) :: s0, s1, s2, s3, s4, s5, s6, s7
      integer :: k, n, n8
      n = size(x)
      n8 = n - mod(n, 8)
      s0 = 0.0_dp
      s1 = 0.0_dp
      s2 = 0.0_dp
      s3 = 0.0_dp
      s4 = 0.0_dp
      s5 = 0.0_dp
      s6 = 0.0_dp
      s7 = 0.0_dp
      do k = 1, n8, 8
         s0 = s0 + x(k)*y(k)
         s1 = s1 + x(k + 1)*y(k + 1)
         s2 = s2 + x(k + 2)*y(k + 2)
         s3 = s3 + x(k + 3)*y(k + 3)
         s4 = s4 + x(k + 4)*y(k + 4)
         s5 = s5 + x(k + 5)*y(k + 5)
         s6 = s6 + x(k + 6)*y(k + 6)
         s7 = s7 + x(k + 7)*y(k + 7)
      end do
      do k = n8 + 1, n
         s0 = s0 + x(k)*y(k)
      end do
      s = ((s0 + s4) + (s1 + s5)) + ((s2 + s6) + (s3 + s7))
   end function dot
end module skyline_solver
