!> The numerical factorization of the MUMPS solver (`mumps_solver`): the checks before MUMPS
!! is called (values outside the pattern, NaN or Inf, a zero or negative diagonal), the
!! symmetric scaling to a unit diagonal, the retries after a workspace error, and MUMPS's
!! verdict (null pivot rows, negative pivots).
!!
!! Why SYM = 2 and not SYM = 1.  The systems are symmetric positive definite
!! when the model is restrained, and that is exactly what must be checked:
!! MUMPS's SPD mode (SYM = 1, LDL^T without pivoting) accepts the round-off
!! pivot of a rigid-body mode without a word (measured with MUMPS 5.5.1: a
!! free chain of springs factorizes with INFOG(1) = 0 and no negative pivot),
!! and it ignores the null-pivot detection ICNTL(24).  The general symmetric
!! mode (SYM = 2) with threshold pivoting (CNTL(1) = 0.01, the default)
!! detects null pivot rows and lists their equations, and costs the same on
!! an SPD matrix (plane-strain Q4 block, 5e5 equations, the same ordering:
!! same factor size, factorization time within the noise of the run).
!!
!! The singularity test is the skyline solver's.  The matrix is scaled
!! symmetrically to a unit diagonal, D^(-1/2) K D^(-1/2) with D = diag(K)
!! (ICNTL(8) = -1, COLSCA = ROWSCA = 1/sqrt(k_jj)), and a pivot row is null
!! when its largest entry is at most `pivot_tol` (CNTL(3) = -pivot_tol, an
!! absolute threshold on the scaled matrix, ICNTL(24) = 1).  For a diagonal
!! pivot that is d_j <= pivot_tol * k_jj, the skyline criterion; the first
!! null pivot row names the failed equation (PIVNUL_LIST).  A zero or
!! negative diagonal (which no positive definite matrix has, and which the
!! scaling cannot take) fails before MUMPS is called, naming its equation;
!! negative pivots that MUMPS finds with a positive diagonal (INFOG(12), the
!! inertia) fail without an equation, which MUMPS cannot tell.
!!
!! Ref: MUMPS 5.5 Users' guide, ICNTL(8), (14), (24), CNTL(1), (3), INFOG(12), (28),
!!      PIVNUL_LIST.
submodule(mumps_solver) mumps_solver_factorize
   implicit none

   !> Workspace errors that a larger relaxation ICNTL(14) cures.
   integer, parameter :: WORKSPACE_ERRORS(4) = [-8, -9, -17, -20]
   !> Attempts of a factorization, doubling ICNTL(14) after each workspace error.
   integer, parameter :: MAX_ATTEMPTS = 4

contains

   !> Numerical factorization of the assembled values (see the header above
   !! for what fails and how).  A workspace error of MUMPS is retried with a
   !! doubled relaxation ICNTL(14), up to MAX_ATTEMPTS times.
   module subroutine mumps_factorize(this, status)
      class(mumps_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status  !! set only on failure
      integer :: attempt, j, jbad

      select case (this%state)
      case (ST_EMPTY)
         call status%set(STAT_SOLVER, 'mumps solver: factorize called before analyse')
         return
      case (ST_FACTORED, ST_FAILED)
                  call status%set(STAT_SOLVER, 'mumps solver: factorize called twice on the '// &
            'same values (call restore_base or zero and assemble again)')
         return
      end select
      if (this%n_outside > 0) then
         call fail(this, status, STAT_SOLVER, 'mumps solver: '//itoa(int(this%n_outside))// &
            ' assembled entries lie outside the pattern given to analyse (first at row '// &
            itoa(this%first_outside(1))//', column '//itoa(this%first_outside(2))//')', 0)
         return
      end if
      if (this%neq == 0) then
         call succeed(this)
         return
      end if
      if (.not. this%analysed) then
         call this%run_analysis(status)
         if (.not. status%ok()) then
            this%bad_eq = 0
            this%fail_msg = status%message
            this%state = ST_FAILED
            return
         end if
      end if
      associate (id => this%mumps%id)
         if (.not. all(ieee_is_finite(id%a))) then
            call fail(this, status, STAT_SOLVER, &
               'mumps solver: the assembled matrix holds NaN or Inf', 0)
            return
         end if
         ! a positive definite matrix has a positive diagonal: the first that
         ! is not fails here, named, and the rest is scaled to a unit diagonal
         jbad = 0
         do j = 1, this%neq
            if (.not. (id%a(this%cp(j)) > 0.0_dp)) then
               if (jbad == 0) jbad = j
            else
               id%colsca(j) = 1.0_dp/sqrt(id%a(this%cp(j)))
            end if
         end do
         if (jbad > 0) then
            this%stats%negative_pivots = count(id%a(this%cp(1:)) < 0.0_dp)
            call fail(this, status, STAT_SINGULAR, &
               'singular or unrestrained model: zero or negative pivot at equation '//itoa(jbad)// &
               ' (diagonal = '//rtoa(id%a(this%cp(jbad)))//', a positive definite matrix has '// &
               'none)', jbad)
            return
         end if
         do attempt = 1, MAX_ATTEMPTS
            call this%mumps%run(JOB_FACTORIZE)
            if (all(id%infog(1) /= WORKSPACE_ERRORS)) exit
            if (attempt < MAX_ATTEMPTS) id%icntl(14) = 2*max(id%icntl(14), 20)
         end do
         if (id%infog(1) < 0) then
            if (id%infog(1) == -10) then
               call fail(this, status, STAT_SINGULAR, 'singular or unrestrained model: '// &
                  mumps_error_text(id%infog(1), id%infog(2))//'; the equation cannot be told', 0)
            else
               call fail(this, status, STAT_SOLVER, 'mumps solver: factorization failed: '// &
                  mumps_error_text(id%infog(1), id%infog(2)), 0)
            end if
            return
         end if
         this%stats%negative_pivots = id%infog(12)
         this%stats%nnz_factor = mumps_size(id%infog(29))
         if (id%infog(28) > 0) then
            j = id%pivnul_list(1)
            call fail(this, status, STAT_SINGULAR, &
               'singular or unrestrained model: zero pivot at equation '//itoa(j)//' (MUMPS: '// &
               itoa(id%infog(28))//' null pivot row(s), no entry above '//rtoa(this%pivot_tol)// &
               ' of the diagonal)', j)
            return
         end if
         if (id%infog(12) > 0) then
            call fail(this, status, STAT_SINGULAR, &
               'singular or unrestrained model: the matrix is not positive definite (MUMPS: '// &
               itoa(id%infog(12))//' negative pivot(s)); the equation cannot be told', 0)
            return
         end if
      end associate
      call succeed(this)
   end subroutine mumps_factorize

   !> Record a valid factorization.
   subroutine succeed(this)
      class(mumps_solver_t), intent(inout) :: this
      this%stats%factorizations = this%stats%factorizations + 1
      this%bad_eq = 0
      this%state = ST_FACTORED
      call update_memory(this)
   end subroutine succeed

   !> Record a failed factorization.
   subroutine fail(this, status, code, msg, eq)
      class(mumps_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer, intent(in) :: code
      character(len=*), intent(in) :: msg
      integer, intent(in) :: eq
      this%bad_eq = eq
      this%fail_msg = msg
      this%state = ST_FAILED
      call status%set(code, msg)
   end subroutine fail
end submodule mumps_solver_factorize
