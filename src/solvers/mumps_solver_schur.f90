!> The Schur complement of the MUMPS solver (`mumps_solver`): a factorization that keeps a
!! set of equations out of the elimination and returns their dense Schur complement, and the
!! condensation and expansion of right-hand sides through it (MUMPS's ICNTL(19), ICNTL(26)).
!! Ref: MUMPS 5.5 Users' guide, sec. 5.15 (Schur complement).
submodule(mumps_solver) mumps_solver_schur
   implicit none

contains

   !> Factorize the assembled values with the equations `vars` kept out of
   !! the elimination, and return their dense Schur complement
   !!
   !!     s = K_cc - K_cb K_bb^-1 K_bc      (c = vars, b = the others)
   !!
   !! from the factorization itself (MUMPS's Schur option: ICNTL(19) = 1,
   !! SIZE_SCHUR, LISTVAR_SCHUR; centralized on the host).  Only K_bb is
   !! factorized, with the tests of `factorize` (its null pivots are named);
   !! MUMPS's analysis runs with the Schur variables at the first call (the
   !! only analysis when no plain factorization came before), later calls with
   !! the same variables reuse it.  MUMPS returns one triangle of the
   !! symmetric complement (the other holds no valid data): `s` is made whole
   !! from it.  MUMPS computes the complement of the matrix as scaled by
   !! `factorize` (D^-1/2 K D^-1/2); `s` is scaled back.  After this call the
   !! solver solves only through `schur_condense` / `schur_expand`.
   !! The condensation and the expansion below scale their vectors alike
   !! (measured with MUMPS 5.5.1: REDRHS is the scaled system's).
   !! Ref: MUMPS 5.5 Users' guide, sec. 5.15 (Schur complement), ICNTL(19).
   module subroutine mumps_factorize_schur(this, vars, s, status)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(in) :: vars(:)            !! the Schur variables (distinct equations)
      real(dp), intent(out) :: s(:, :)          !! (size(vars), size(vars)) the Schur complement
      type(status_t), intent(inout) :: status   !! set only on failure
      integer :: nc, i, j
      real(dp) :: di, dj
      nc = size(vars)
      if (this%state /= ST_ASSEMBLING .or. .not. this%mumps%started()) then
         call status%set(STAT_SOLVER, &
            'mumps solver: factorize_schur needs assembled values (restore_base first)')
         return
      end if
      if (nc < 1 .or. nc >= this%neq .or. any(vars < 1 .or. vars > this%neq)) then
         call status%set(STAT_SOLVER, &
            'mumps solver: invalid Schur variables (need 1 to neq-1 equations within 1..'// &
            itoa(this%neq)//')')
         return
      end if
      associate (id => this%mumps%id)
         if (this%nschur /= nc) then
            if (associated(id%listvar_schur)) deallocate (id%listvar_schur)
            if (associated(id%schur)) deallocate (id%schur)
            if (associated(id%redrhs)) deallocate (id%redrhs)
            allocate (id%listvar_schur(nc), id%schur(int(nc, i8)*int(nc, i8)), id%redrhs(nc))
            this%nschur = nc
            this%analysed = .false.
         else if (any(id%listvar_schur /= vars) .or. id%icntl(19) /= 1) then
            this%analysed = .false.
         end if
         if (.not. this%analysed) then
            id%listvar_schur(:) = vars
            id%size_schur = nc
            id%icntl(19) = 1                 ! centralized Schur complement on the host
            id%schur_lld = nc
            id%lredrhs = nc
            call this%run_analysis(status)
            if (.not. status%ok()) then
               this%fail_msg = status%message
               this%state = ST_FAILED
               return
            end if
         end if
      end associate
      call this%factorize(status)
      if (.not. status%ok()) return
      associate (id => this%mumps%id)
         ! the valid triangle: the upper one of the column-major array
         ! (MUMPS: the lower triangle by rows)
         do j = 1, nc
            dj = id%colsca(vars(j))
            do i = 1, j
               di = id%colsca(vars(i))
               s(i, j) = id%schur(i + (int(j, i8) - 1)*nc)/(di*dj)
               s(j, i) = s(i, j)
            end do
         end do
      end associate
      call update_memory(this)
   end subroutine mumps_factorize_schur

   !> Condensation of a right-hand side onto the Schur variables (JOB = 3,
   !! ICNTL(26) = 1): g = b_c - K_cb K_bb^-1 b_b.  MUMPS keeps what the
   !! expansion needs: the next call on this solver must be `schur_expand`
   !! (or another condensation, which replaces it).
   module subroutine mumps_schur_condense(this, b, g, status)
      class(mumps_solver_t), intent(inout) :: this
      real(dp), intent(in) :: b(:)              !! (neq) right-hand side
      real(dp), intent(out) :: g(:)             !! (n_c) reduced right-hand side, order of vars
      type(status_t), intent(inout) :: status
      if (.not. schur_ready(this, size(b), size(g), status)) return
      associate (id => this%mumps%id)
         id%rhs(:) = b
         id%nrhs = 1
         id%lrhs = this%neq
         id%icntl(26) = 1
         call this%mumps%run(JOB_SOLVE)
         id%icntl(26) = 0
         if (id%infog(1) < 0) then
            call status%set(STAT_SOLVER, &
               'mumps solver: condensation of a right-hand side failed: '// &
               mumps_error_text(id%infog(1), id%infog(2)))
            return
         end if
         ! MUMPS condenses the scaled system: g = D_c^(1/2) times its reduced right-hand side
         g = id%redrhs(1:this%nschur)/id%colsca(id%listvar_schur)
      end associate
      this%stats%solves = this%stats%solves + 1
   end subroutine mumps_schur_condense

   !> Expansion (JOB = 3, ICNTL(26) = 2): the whole solution x (neq) of the
   !! right-hand side of the last `schur_condense`, given its values xc at the
   !! Schur variables: x_b = K_bb^-1 (b_b - K_bc xc), x_c = xc.
   module subroutine mumps_schur_expand(this, xc, x, status)
      class(mumps_solver_t), intent(inout) :: this
      real(dp), intent(in) :: xc(:)             !! (n_c) solution at the Schur variables
      real(dp), intent(out) :: x(:)             !! (neq) the whole solution
      type(status_t), intent(inout) :: status
      if (.not. schur_ready(this, size(x), size(xc), status)) return
      associate (id => this%mumps%id)
         ! the scaled system's unknowns at the Schur variables: D_c^(1/2) xc
         id%redrhs(1:this%nschur) = xc/id%colsca(id%listvar_schur)
         id%nrhs = 1
         id%lrhs = this%neq
         id%icntl(26) = 2
         call this%mumps%run(JOB_SOLVE)
         id%icntl(26) = 0
         if (id%infog(1) < 0) then
            call status%set(STAT_SOLVER, 'mumps solver: expansion of a Schur solution failed: '// &
               mumps_error_text(id%infog(1), id%infog(2)))
            return
         end if
         x = id%rhs
      end associate
   end subroutine mumps_schur_expand

   !> A factorization with a Schur complement, and vectors of the right lengths.
   logical function schur_ready(this, nb, nc, status) result(ok)
      class(mumps_solver_t), intent(in) :: this
      integer, intent(in) :: nb, nc
      type(status_t), intent(inout) :: status
      ok = this%ready_to_solve(nb, status)
      if (.not. ok) return
      ok = this%nschur > 0 .and. nc == this%nschur
      if (.not. ok) call status%set(STAT_SOLVER, 'mumps solver: no Schur complement of '// &
         itoa(nc)//' variables to condense onto (factorize_schur first)')
   end function schur_ready
end submodule mumps_solver_schur
