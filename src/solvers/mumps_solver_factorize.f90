!> The numerical factorization of the MUMPS solver (`mumps_solver`, whose header says what
!! fails and how): the checks before MUMPS is called (values outside the pattern, NaN or Inf,
!! a zero or negative diagonal), the symmetric scaling to a unit diagonal, the retries after
!! a workspace error, and MUMPS's verdict (null pivot rows, negative pivots).
submodule(mumps_solver) mumps_solver_factorize
   implicit none

   !> Workspace errors that a larger relaxation ICNTL(14) cures.
   integer, parameter :: WORKSPACE_ERRORS(4) = [-8, -9, -17, -20]
   !> Attempts of a factorization, doubling ICNTL(14) after each workspace error.
   integer, parameter :: MAX_ATTEMPTS = 4

contains

   !> Numerical factorization of the assembled values (see the module header
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
