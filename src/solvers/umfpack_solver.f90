!> Sparse direct solver: SuiteSparse UMFPACK (unsymmetric multifrontal LU)
!! behind the `linear_solver_t` interface.
!!
!! Storage.  The whole symmetric matrix (both triangles) in 0-based
!! compressed-column form, as UMFPACK takes it: `ap(0:neq)` column pointers,
!! `ai(:)` row indices, **sorted within each column**, and `ax(:)` values.
!! The pattern is built once by `analyse` from the equation graph (every
!! coupling in both triangles, the diagonal always); element matrices are
!! scattered straight into `ax`, locating (i, j) by a binary search of the
!! sorted rows of column j: O(log nnz_j) per entry, no dense or coordinate
!! intermediate.
!!
!! Life cycle.  `analyse` builds the pattern and runs UMFPACK's symbolic
!! analysis (fill-reducing ordering: AMD on the symmetric pattern, "symmetric"
!! strategy, which prefers diagonal pivots) on the pattern alone, so it is
!! kept for as long as the pattern does not change, i.e. across increments.
!! `factorize` runs the numeric factorization on the current values;
!! `solve` may be called any number of times per factorization, without
!! allocating anything: the solution and UMFPACK's workspace are kept with
!! the pattern (umfpack_di_wsolve).
!!
!! Iterative refinement.  UMFPACK refines every solution by default (up to 2
!! steps, Control[UMFPACK_IRSTEP]), which doubles the cost of a solve and
!! buys nothing on these systems: symmetric positive definite, factorized
!! with diagonal pivots, whose backward error is already at round-off.
!! Measured without it: residuals and agreement with the skyline solver
!! unchanged at round-off on the unit tests, the example decks and the
!! benchmark mesh (docs/solvers.md).  `refine_steps` sets it (before
!! `analyse`); the default is 0.
!!
!! Singular matrices.  UMFPACK reports an exactly zero pivot as a warning
!! (status +1); a rigid-body mode usually gives a round-off pivot instead,
!! which UMFPACK accepts.  After every numeric factorization the diagonal
!! of U is therefore checked with the skyline solver's test: pivot k, taken
!! at row P(k), column Q(k) of the scaled matrix R A, fails when
!! |u_kk| <= pivot_tol * |(R A)(P(k), Q(k))|.  For a diagonal pivot
!! (P(k) = Q(k), the rule for an SPD matrix) u_kk / (R A)_pp is the LDL^T
!! pivot d_k / k_pp of the permuted matrix, so both solvers apply the same
!! criterion and name the failed equation Q(k) + 1.
!!
!! Ref: T. A. Davis, "Algorithm 832: UMFPACK V4.3 - an unsymmetric-pattern
!!      multifrontal method", ACM TOMS 30 (2004) 196-199; UMFPACK User Guide.
module umfpack_solver
   use, intrinsic :: iso_c_binding, only: c_int, c_double, c_ptr, c_null_ptr, c_loc, c_associated
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp, i8
   use errors, only: status_t, fatal_internal, STAT_SINGULAR, STAT_SOLVER
   use strings, only: itoa, rtoa
   use sorting, only: insertion_sort
   use linear_solver, only: linear_solver_t, solver_stats_t, ST_EMPTY, ST_ASSEMBLING, &
         ST_FACTORED, ST_FAILED
   use umfpack_c
   implicit none
   private

   public :: umfpack_solver_t, umfpack_status_text


   !> UMFPACK LU solver with a symbolic analysis kept per sparsity pattern.
   type, extends(linear_solver_t) :: umfpack_solver_t
      !> Relative pivot threshold, the same as the skyline solver's.
      real(dp) :: pivot_tol = 1.0e-12_dp
      !> Steps of iterative refinement per solve, Control[UMFPACK_IRSTEP]
      !! (UMFPACK's default is 2; see the module header).  Read by `analyse`.
      integer :: refine_steps = 0
      integer(c_int), allocatable, private :: ap(:)   ! (0:neq) column pointers, 0-based
      integer(c_int), allocatable, private :: ai(:)   ! (nnz) row indices, 0-based,
                                                      ! sorted per column
      real(c_double), allocatable, private :: ax(:)   ! (nnz) values
      real(c_double), allocatable, private :: base(:) ! stored copy of K_AB
      real(c_double), allocatable, private :: x(:)    ! (neq) solution of a solve
      real(c_double), allocatable, private :: w(:)    ! (neq or 5 neq) workspace of a solve
      integer(c_int), allocatable, private :: wi(:)   ! (neq) workspace of a solve
      real(c_double), private :: control(UMFPACK_CONTROL) = 0.0_c_double
      real(c_double), private :: info(UMFPACK_INFO) = 0.0_c_double
      type(c_ptr), private :: symbolic = c_null_ptr
      type(c_ptr), private :: numeric = c_null_ptr
      integer(i8), private :: symbolic_bytes = 0, numeric_bytes = 0
      integer, private :: symbolic_count = 0
   contains
      procedure :: analyse => umf_analyse
      procedure :: zero => umf_zero
      procedure :: add_element => umf_add_element
      procedure :: store_base => umf_store_base
      procedure :: restore_base => umf_restore_base
      procedure :: factorize => umf_factorize
      procedure :: solve => umf_solve
      procedure :: free => umf_free
      procedure :: name => umf_name
      procedure :: nnz => umf_nnz
      procedure :: symbolic_analyses => umf_symbolic_analyses
      final :: umf_finalize
   end type umfpack_solver_t

contains

   !> Pattern of the full symmetric matrix from the CSR equation graph, and
   !! the symbolic analysis of it.
   !!
   !! The graph may list each coupling once (either triangle) or twice; the
   !! CSC pattern holds (i, j) and (j, i) for each, and every diagonal.
   !! O(neq + nnz log nnz_j) work.  STAT_SOLVER for an invalid graph or a
   !! failed symbolic analysis (status text from UMFPACK).
   subroutine umf_analyse(this, neq, xadj, adjncy, status)
      class(umfpack_solver_t), intent(inout) :: this
      integer, intent(in) :: neq          !! number of equations
      integer, intent(in) :: xadj(:)      !! (neq+1) 1-based CSR row pointers of the graph
      integer, intent(in) :: adjncy(:)    !! columns coupled to each row, diagonal included
      type(status_t), intent(inout) :: status
      integer, allocatable :: cnt(:), pos(:)
      integer :: r, c, p, j, k, q, ierr, last
      integer(i8) :: nnz8
      integer(c_int) :: st

      call this%free()
      if (neq < 0) then
         call status%set(STAT_SOLVER, 'umfpack solver: negative number of equations '//itoa(neq))
         return
      end if
      if (neq > 0) then
         if (size(xadj) < neq + 1) then
            call status%set(STAT_SOLVER, 'umfpack solver: invalid equation graph (xadj has '// &
                            itoa(size(xadj))//' entries, needs '//itoa(neq + 1)//')')
            return
         end if
         if (xadj(1) /= 1 .or. xadj(neq + 1) - 1 > size(adjncy)) then
            call status%set(STAT_SOLVER, &
                            'umfpack solver: invalid equation graph (xadj must start at 1 '// &
                            'and end within adjncy)')
            return
         end if
      end if

      ! count: every listed coupling in both columns, plus the diagonal
      allocate (cnt(max(neq, 1)))
      cnt = 1
      do r = 1, neq
         if (xadj(r + 1) < xadj(r)) then
            call status%set(STAT_SOLVER, &
                            'umfpack solver: invalid equation graph (xadj decreases at row '// &
                            itoa(r)//')')
            return
         end if
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c < 1 .or. c > neq) then
               call status%set(STAT_SOLVER, 'umfpack solver: invalid equation graph (row '// &
                               itoa(r)// &
                               ' lists equation '//itoa(c)//')')
               return
            end if
            if (c == r) cycle
            cnt(c) = cnt(c) + 1
            cnt(r) = cnt(r) + 1
         end do
      end do
      nnz8 = sum(int(cnt(1:neq), i8))
      if (nnz8 > int(huge(1_c_int), i8)) then
         call status%set(STAT_SOLVER, 'umfpack solver: '//itoa(neq)// &
                         ' equations give more than 2^31 '// &
                         'matrix entries (the int version of UMFPACK cannot take them)')
         return
      end if
      allocate (this%ap(0:neq), pos(max(neq, 1)), stat=ierr)
      if (ierr == 0) allocate (this%ai(nnz8), this%ax(nnz8), stat=ierr)
      if (ierr /= 0) then
         call status%set(STAT_SOLVER, 'umfpack solver: cannot allocate a pattern of '// &
                         itoa(int(nnz8))//' entries')
         call this%free()
         return
      end if
      this%ap(0) = 0
      do j = 1, neq
         this%ap(j) = this%ap(j - 1) + cnt(j)
      end do
      ! fill (1-based positions pos(j) into ai), diagonal first
      do j = 1, neq
         pos(j) = this%ap(j - 1) + 1
         this%ai(pos(j)) = j - 1
         pos(j) = pos(j) + 1
      end do
      do r = 1, neq
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c == r) cycle
            this%ai(pos(c)) = r - 1
            pos(c) = pos(c) + 1
            this%ai(pos(r)) = c - 1
            pos(r) = pos(r) + 1
         end do
      end do
      ! sort every column and drop duplicates (a coupling listed twice)
      q = 0
      last = 0
      do j = 1, neq
         k = this%ap(j - 1) + 1
         call insertion_sort(this%ai(k:this%ap(j)))
         do p = k, this%ap(j)
            if (p > k) then
               if (this%ai(p) == this%ai(p - 1)) cycle
            end if
            q = q + 1
            this%ai(q) = this%ai(p)
         end do
         this%ap(j - 1) = last
         last = q
      end do
      this%ap(neq) = q
      if (q < size(this%ai)) then
         this%ai = this%ai(1:q)
         deallocate (this%ax)
         allocate (this%ax(q))
      end if
      this%ax = 0.0_c_double
      this%neq = neq
      this%state = ST_ASSEMBLING
      this%stats%neq = neq
      this%stats%nnz_matrix = int(q, i8)

      call umfpack_di_defaults(this%control)
      this%control(UMFPACK_STRATEGY + 1) = UMFPACK_STRATEGY_SYMMETRIC
      this%control(UMFPACK_PRL + 1) = 0.0_c_double
      this%control(UMFPACK_IRSTEP + 1) = real(max(0, this%refine_steps), c_double)
      allocate (this%x(neq), this%wi(neq), this%w(merge(5, 1, this%refine_steps > 0)*neq))
      if (neq > 0) then
         st = umfpack_di_symbolic(int(neq, c_int), int(neq, c_int), this%ap, this%ai, c_null_ptr, &
                                  this%symbolic, this%control, this%info)
         if (st /= UMFPACK_OK) then
            call status%set(STAT_SOLVER, 'umfpack solver: symbolic analysis failed: '// &
                            umfpack_status_text(st))
            call this%free()
            return
         end if
         this%symbolic_count = this%symbolic_count + 1
         this%symbolic_bytes = int(this%info(UMFPACK_SYMBOLIC_SIZE + &
                                             1)*this%info(UMFPACK_SIZE_OF_UNIT + 1), i8)
      end if
      call update_memory(this)
   end subroutine umf_analyse

   !> Memory held: pattern, values, stored copy, symbolic and numeric objects.
   subroutine update_memory(this)
      class(umfpack_solver_t), intent(inout) :: this
      integer(i8) :: m
      m = this%symbolic_bytes + this%numeric_bytes
      if (allocated(this%ap)) m = m + 4_i8*size(this%ap, kind=i8)
      if (allocated(this%ai)) m = m + 4_i8*size(this%ai, kind=i8)
      if (allocated(this%ax)) m = m + 8_i8*size(this%ax, kind=i8)
      if (allocated(this%base)) m = m + 8_i8*size(this%base, kind=i8)
      if (allocated(this%x)) then
         m = m + 8_i8*(size(this%x, kind=i8) + size(this%w, kind=i8)) + 4_i8*size(this%wi, kind=i8)
      end if
      this%stats%memory_bytes = m
   end subroutine update_memory

   !> Set every assembled value to zero (the pattern and the symbolic analysis stay).
   subroutine umf_zero(this)
      class(umfpack_solver_t), intent(inout) :: this
      if (this%state == ST_EMPTY) then
         call fatal_internal('umfpack solver: zero called before analyse', 'umfpack_solver.f90', &
                             __LINE__)
      end if
      call drop_numeric(this)
      this%ax = 0.0_c_double
      this%n_outside = 0
      this%first_outside = 0
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine umf_zero

   !> Scatter a symmetric element matrix into both triangles.
   !!
   !! The skyline rule, mirrored: ke(a, b) with i = ieq(a) <= j = ieq(b) is
   !! added to K(i, j) and, for i < j, to K(j, i); so tied dofs sum onto the
   !! diagonal exactly as in the skyline solver and the matrix stays exactly
   !! symmetric.  Dofs with ieq <= 0 are skipped; a nonzero entry outside the
   !! pattern (or ieq > neq) is counted and reported by the next `factorize`.
   subroutine umf_add_element(this, ieq, ke)
      class(umfpack_solver_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)       !! global equation of each element dof
      real(dp), intent(in) :: ke(:, :)    !! element matrix, size(ieq) square, symmetric
      integer :: ia, ib, i, j, nd, p

      call this%check_element(ieq, ke, 'umfpack_solver.f90', __LINE__)
      nd = size(ieq)
      do ib = 1, nd
         j = ieq(ib)
         if (j <= 0) cycle
         do ia = 1, nd
            i = ieq(ia)
            if (i <= 0 .or. i > j) cycle
            if (j <= this%neq) then
               p = locate(this, i, j)
               if (p > 0) then
                  this%ax(p) = this%ax(p) + ke(ia, ib)
                  if (i < j) then
                     p = locate(this, j, i)
                     this%ax(p) = this%ax(p) + ke(ia, ib)
                  end if
                  cycle
               end if
            end if
            if (.not. (abs(ke(ia, ib)) <= 0.0_dp)) then
               if (this%n_outside == 0) this%first_outside = [i, j]
               this%n_outside = this%n_outside + 1
            end if
         end do
      end do
   end subroutine umf_add_element

   !> Position (1-based, in ai/ax) of entry (i, j), 1-based indices; 0 if
   !! the pattern does not hold it.  Binary search of column j's sorted rows.
   pure integer function locate(this, i, j) result(p)
      class(umfpack_solver_t), intent(in) :: this
      integer, intent(in) :: i, j
      integer :: lo, hi, mid, r
      r = i - 1
      lo = this%ap(j - 1) + 1
      hi = this%ap(j)
      p = 0
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (this%ai(mid) == r) then
            p = mid
            return
         else if (this%ai(mid) < r) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
   end function locate

   !> Keep a copy of the assembled values (K_AB) for `restore_base`.
   subroutine umf_store_base(this)
      class(umfpack_solver_t), intent(inout) :: this
      if (this%state /= ST_ASSEMBLING) call fatal_internal( &
         'umfpack solver: store_base needs assembled values (call it before factorize)', &
         'umfpack_solver.f90', __LINE__)
      this%base = this%ax
      this%base_outside = this%n_outside
      this%base_first_outside = this%first_outside
      call update_memory(this)
   end subroutine umf_store_base

   !> Put back the values kept by `store_base`, discarding springs and factors
   !! (the symbolic analysis is kept: the pattern has not changed).
   subroutine umf_restore_base(this)
      class(umfpack_solver_t), intent(inout) :: this
      if (.not. allocated(this%base) .or. this%state == ST_EMPTY) call fatal_internal( &
         'umfpack solver: restore_base without store_base', 'umfpack_solver.f90', __LINE__)
      call drop_numeric(this)
      this%ax(:) = this%base(:)
      this%n_outside = this%base_outside
      this%first_outside = this%base_first_outside
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine umf_restore_base

   !> Free the numeric object, if any.
   subroutine drop_numeric(this)
      class(umfpack_solver_t), intent(inout) :: this
      if (c_associated(this%numeric)) call umfpack_di_free_numeric(this%numeric)
      this%numeric = c_null_ptr
      this%numeric_bytes = 0
   end subroutine drop_numeric

   !> Numeric LU factorization of the assembled values, then the pivot check.
   !!
   !! Any UMFPACK status other than UMFPACK_OK fails: +1 (singular matrix)
   !! gives STAT_SINGULAR naming the equation of the first zero diagonal of U
   !! in elimination order; errors give STAT_SOLVER with UMFPACK's meaning.
   !! A round-off or negative pivot found by the check below gives
   !! STAT_SINGULAR with the skyline solver's message.
   subroutine umf_factorize(this, status)
      class(umfpack_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status  !! set only on failure
      integer(c_int) :: st

      select case (this%state)
      case (ST_EMPTY)
         call status%set(STAT_SOLVER, 'umfpack solver: factorize called before analyse')
         return
      case (ST_FACTORED, ST_FAILED)
         call status%set(STAT_SOLVER, 'umfpack solver: factorize called twice on the same '// &
                         'values (call restore_base or zero and assemble again)')
         return
      end select
      if (this%n_outside > 0) then
         call fail(this, status, STAT_SOLVER, 'umfpack solver: '//itoa(int(this%n_outside))// &
                   ' assembled entries lie outside the pattern given to analyse (first at row '// &
                   itoa(this%first_outside(1))//', column '//itoa(this%first_outside(2))//')', 0)
         return
      end if
      if (this%neq == 0) then
         this%stats%pivot_ratio = 1.0_dp
         this%stats%factorizations = this%stats%factorizations + 1
         this%state = ST_FACTORED
         return
      end if
      if (.not. all(ieee_is_finite(this%ax))) then
         call fail(this, status, STAT_SOLVER, &
                   'umfpack solver: the assembled matrix holds NaN or Inf', 0)
         return
      end if
      call drop_numeric(this)
      st = umfpack_di_numeric(this%ap, this%ai, this%ax, this%symbolic, this%numeric, &
                              this%control, this%info)
      if (st == UMFPACK_OK .or. st == UMFPACK_WARNING_singular_matrix) then
         this%numeric_bytes = int(this%info(UMFPACK_NUMERIC_SIZE + &
                                            1)*this%info(UMFPACK_SIZE_OF_UNIT + 1), i8)
         this%stats%nnz_factor = int(this%info(UMFPACK_LNZ + 1) + this%info(UMFPACK_UNZ + 1), i8) &
               - this%neq
         call update_memory(this)
      end if
      if (st == UMFPACK_WARNING_singular_matrix .or. st == UMFPACK_OK) then
         call check_pivots(this, st, status)
         if (.not. status%ok()) return
         this%stats%factorizations = this%stats%factorizations + 1
         this%bad_eq = 0
         this%state = ST_FACTORED
         return
      end if
      call fail(this, status, STAT_SOLVER, 'umfpack solver: numeric factorization failed: '// &
                umfpack_status_text(st), 0)
   end subroutine umf_factorize

   !> Check the diagonal of U pivot by pivot (see the module header), record
   !! the pivot statistics, and fail on the first zero, round-off or negative
   !! pivot.  `st` is the status of umfpack_di_numeric (0 or +1).
   subroutine check_pivots(this, st, status)
      class(umfpack_solver_t), intent(inout) :: this
      integer(c_int), intent(in) :: st
      type(status_t), intent(inout) :: status
      integer(c_int), allocatable, target :: p(:), q(:)
      real(c_double), allocatable, target :: dx(:), rs(:)
      integer(c_int) :: do_recip, st2
      integer :: k, n, row, col, nneg, pos, kbad
      real(dp) :: akk, ratio, rmin, ukk, abad
      logical :: symmetric_pivots

      n = this%neq
      allocate (p(n), q(n), dx(n), rs(n))
      st2 = umfpack_di_get_numeric(c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, c_null_ptr, &
                                   c_null_ptr, &
                                   c_loc(p), c_loc(q), c_loc(dx), do_recip, c_loc(rs), this%numeric)
      if (st2 /= UMFPACK_OK) then
         if (st == UMFPACK_WARNING_singular_matrix) then
            call fail(this, status, STAT_SINGULAR, &
                      'singular or unrestrained model: UMFPACK found the '// &
                      'matrix singular; the equation cannot be told (reading the factors &
                      &failed: '// &
                      umfpack_status_text(st2)//')', 0)
         else
            call fail(this, status, STAT_SOLVER, 'umfpack solver: cannot read the factors: '// &
                      umfpack_status_text(st2), 0)
         end if
         return
      end if
      symmetric_pivots = all(p == q)
      rmin = 1.0_dp
      nneg = 0
      kbad = 0
      abad = 0.0_dp
      do k = 1, n
         row = p(k) + 1
         col = q(k) + 1
         ! the entry pivoted on, before elimination, in the scaled matrix R A
         pos = locate(this, row, col)
         akk = 0.0_dp
         if (pos > 0) akk = abs(this%ax(pos))
         if (.not. (akk > 0.0_dp)) akk = maxval(abs(this%ax(this%ap(col - 1) + 1:this%ap(col))))
         if (do_recip /= 0) then
            akk = akk*rs(row)
         else
            akk = akk/rs(row)
         end if
         ukk = dx(k)
         if (symmetric_pivots .and. ukk < 0.0_dp) nneg = nneg + 1
         ratio = 0.0_dp
         if (akk > 0.0_dp) ratio = abs(ukk)/akk
         rmin = min(rmin, ratio)
         if (kbad == 0) then
            if (.not. (abs(ukk) > this%pivot_tol*akk) .or. (symmetric_pivots .and. ukk < 0.0_dp)) &
                  then
               kbad = k
               abad = akk
            end if
         end if
      end do
      this%stats%negative_pivots = nneg
      this%stats%pivot_ratio = rmin
      if (kbad > 0) then
         col = q(kbad) + 1
         call fail(this, status, STAT_SINGULAR, &
                   'singular or unrestrained model: zero or negative pivot at '// &
                   'equation '//itoa(col)//' (pivot = '//rtoa(dx(kbad))//', diagonal = '// &
                   rtoa(abad)// &
                   ', row-scaled, pivot '//itoa(kbad)//' of the LU factors)', col)
         return
      end if
      if (st == UMFPACK_WARNING_singular_matrix) then
         call fail(this, status, STAT_SINGULAR, &
                   'singular or unrestrained model: UMFPACK found the matrix '// &
                   'singular, but no zero diagonal of U could be located: the equation cannot be &
                   &told', 0)
      end if
   end subroutine check_pivots

   !> Record a failed factorization (the numeric object is released).
   subroutine fail(this, status, code, msg, eq)
      class(umfpack_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      integer, intent(in) :: eq
      call drop_numeric(this)
      this%bad_eq = eq
      this%fail_msg = msg
      this%state = ST_FAILED
      call status%set(code, msg)
   end subroutine fail

   !> Solve K x = b with the LU factors; b is overwritten with x, and left
   !! unchanged (status STAT_SOLVER) when there is no valid factorization or
   !! UMFPACK's solve reports any status other than UMFPACK_OK.
   subroutine umf_solve(this, b, status)
      class(umfpack_solver_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)          !! (neq) right-hand side in, solution out
      type(status_t), intent(inout) :: status  !! set only on failure
      integer(c_int) :: st

      if (.not. this%ready_to_solve(size(b), status)) return
      if (this%neq == 0) then
         this%stats%solves = this%stats%solves + 1
         return
      end if
      st = umfpack_di_wsolve(UMFPACK_A, this%ap, this%ai, this%ax, this%x, b, this%numeric, &
                             this%control, &
                             this%info, this%wi, this%w)
      if (st /= UMFPACK_OK) then
         call status%set(STAT_SOLVER, 'umfpack solver: solve failed: '//umfpack_status_text(st))
         return
      end if
      b(:) = this%x
      this%stats%solves = this%stats%solves + 1
   end subroutine umf_solve

   !> Release all storage and UMFPACK objects; the solver is as new.
   subroutine umf_free(this)
      class(umfpack_solver_t), intent(inout) :: this
      call drop_numeric(this)
      if (c_associated(this%symbolic)) call umfpack_di_free_symbolic(this%symbolic)
      this%symbolic = c_null_ptr
      if (allocated(this%ap)) deallocate (this%ap)
      if (allocated(this%ai)) deallocate (this%ai)
      if (allocated(this%ax)) deallocate (this%ax)
      if (allocated(this%base)) deallocate (this%base)
      if (allocated(this%x)) deallocate (this%x, this%w, this%wi)
      call this%reset_common()
      this%symbolic_bytes = 0
      this%numeric_bytes = 0
      this%symbolic_count = 0
   end subroutine umf_free

   !> Release the UMFPACK objects when the solver goes out of scope.
   subroutine umf_finalize(this)
      type(umfpack_solver_t), intent(inout) :: this
      call umf_free(this)
   end subroutine umf_finalize

   function umf_name(this) result(s)
      class(umfpack_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      associate (unused => this)
      end associate
      s = 'umfpack'
   end function umf_name


   !> Entries of the CSC pattern (both triangles).
   pure integer(i8) function umf_nnz(this) result(n)
      class(umfpack_solver_t), intent(in) :: this
      n = 0
      if (allocated(this%ap)) n = int(this%ap(this%neq), i8)
   end function umf_nnz

   !> Symbolic analyses done since the last `free` (1 per pattern).
   pure integer function umf_symbolic_analyses(this) result(n)
      class(umfpack_solver_t), intent(in) :: this
      n = this%symbolic_count
   end function umf_symbolic_analyses

   !> Meaning of an UMFPACK status code.
   pure function umfpack_status_text(st) result(s)
      integer(c_int), intent(in) :: st
      character(len=:), allocatable :: s
      select case (st)
      case (UMFPACK_OK)
         s = 'ok'
      case (UMFPACK_WARNING_singular_matrix)
         s = 'the matrix is singular (UMFPACK_WARNING_singular_matrix)'
      case (UMFPACK_WARNING_determinant_underflow)
         s = 'determinant underflow (UMFPACK_WARNING_determinant_underflow)'
      case (UMFPACK_WARNING_determinant_overflow)
         s = 'determinant overflow (UMFPACK_WARNING_determinant_overflow)'
      case (UMFPACK_ERROR_out_of_memory)
         s = 'out of memory (UMFPACK_ERROR_out_of_memory)'
      case (UMFPACK_ERROR_invalid_Numeric_object)
         s = 'invalid numeric object (UMFPACK_ERROR_invalid_Numeric_object)'
      case (UMFPACK_ERROR_invalid_Symbolic_object)
         s = 'invalid symbolic object (UMFPACK_ERROR_invalid_Symbolic_object)'
      case (UMFPACK_ERROR_argument_missing)
         s = 'a required argument is missing (UMFPACK_ERROR_argument_missing)'
      case (UMFPACK_ERROR_n_nonpositive)
         s = 'the number of equations is not positive (UMFPACK_ERROR_n_nonpositive)'
      case (UMFPACK_ERROR_invalid_matrix)
         s = 'invalid compressed-column matrix (UMFPACK_ERROR_invalid_matrix)'
      case (UMFPACK_ERROR_different_pattern)
         s = 'the pattern changed since the symbolic analysis (UMFPACK_ERROR_different_pattern)'
      case (UMFPACK_ERROR_invalid_system)
         s = 'invalid system (UMFPACK_ERROR_invalid_system)'
      case (UMFPACK_ERROR_invalid_permutation)
         s = 'invalid permutation (UMFPACK_ERROR_invalid_permutation)'
      case (UMFPACK_ERROR_file_IO)
         s = 'file I/O error (UMFPACK_ERROR_file_IO)'
      case (UMFPACK_ERROR_ordering_failed)
         s = 'the fill-reducing ordering failed (UMFPACK_ERROR_ordering_failed)'
      case (UMFPACK_ERROR_internal_error)
         s = 'internal error in UMFPACK (UMFPACK_ERROR_internal_error)'
      case default
         s = 'unknown UMFPACK status '//itoa(int(st))
      end select
   end function umfpack_status_text
end module umfpack_solver
