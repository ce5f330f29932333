!> Sparse direct solver: MUMPS (multifrontal symmetric LDL^T) behind the
!! `linear_solver_t` interface.
!!
!! Storage.  The upper triangle of K (i <= j, diagonal included) in MUMPS's
!! centralized assembled coordinate format (IRN, JCN, A; ICNTL(5) = 0,
!! ICNTL(18) = 0), ordered by columns: column j holds entries
!! `cp(j-1)+1 : cp(j)`, rows sorted ascending, the diagonal last.  The
!! pattern is built once by `analyse`; element matrices are scattered
!! straight into A, locating (i, j) by a binary search of column j's rows.
!!
!! Life cycle.  `analyse` takes the pattern and starts MUMPS; MUMPS's
!! analysis of the pattern (JOB = 1: the fill-reducing ordering, the
!! elimination tree and the memory estimates) runs at the first `factorize`
!! (or earlier by `run_analysis`) and is kept for as long as the pattern
!! holds, i.e. across increments.  It is put off so that a factorization with
!! a Schur complement (`factorize_schur`, whose variables the analysis must
!! know) analyses the pattern once, not once without and once with them.
!! `factorize` runs the numerical factorization (JOB = 2) on the current
!! values, `solve` (JOB = 3) any number of times per factorization.
!!
!! Ordering.  AMD, METIS's nested dissection, SCOTCH or PORD: `mumps_ordering`, which also
!! says which is the default and why.
!!
!! Why SYM = 2 (general symmetric) and not the SPD mode, and the singularity test (the
!! skyline solver's, on the matrix scaled to a unit diagonal): the submodule
!! mumps_solver_factorize.
!!
!! Ref: P. R. Amestoy, I. S. Duff, J. Koster, J.-Y. L'Excellent, "A fully
!!      asynchronous multifrontal solver using distributed dynamic
!!      scheduling", SIAM J. Matrix Anal. Appl. 23 (2001) 15-41;
!!      MUMPS 5.5 Users' guide, ICNTL(7), (8), (24), CNTL(1), (3), INFOG(12),
!!      (28), PIVNUL_LIST; P. R. Amestoy, T. A. Davis, I. S. Duff, "An
!!      approximate minimum degree ordering algorithm", SIAM J. Matrix Anal.
!!      Appl. 17 (1996) 886-905.
module mumps_solver
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp, i8
   use errors, only: status_t, fatal_internal, STAT_SINGULAR, STAT_SOLVER
   use strings, only: itoa, rtoa
   use linear_solver, only: linear_solver_t, ST_EMPTY, ST_ASSEMBLING, ST_FACTORED, ST_FAILED
   use metis_ordering, only: metis_available
   use mumps_instance, only: mumps_instance_t, mumps_error_text, mumps_size, JOB_ANALYSE, &
                             JOB_FACTORIZE, JOB_SOLVE
   use mumps_pattern, only: upper_pattern, column_indices, locate_entry
   use mumps_ordering, only: ORDERING_AMD, ORDERING_SCOTCH, ORDERING_PORD, ORDERING_AUTO, &
                             ORDERING_METIS, ORDERING_DEFAULT, METIS_MIN_NEQ, choose_ordering, &
                             ordering_text, metis_perm_in
   use heap_policy, only: keep_freed_heap
   implicit none
   private

   public :: mumps_solver_t
   ! the ordering codes (module mumps_ordering) are part of this solver's interface
   public :: ORDERING_AMD, ORDERING_SCOTCH, ORDERING_PORD, ORDERING_AUTO, ORDERING_METIS, &
             ORDERING_DEFAULT

   !> MUMPS LDL^T solver with an analysis kept per sparsity pattern.
   type, extends(linear_solver_t) :: mumps_solver_t
      !> Relative pivot threshold, the skyline solver's: a null pivot row of
      !! the unit-diagonal scaled matrix has no entry above it.
      real(dp) :: pivot_tol = 1.0e-12_dp
      !> Fill-reducing ordering, ICNTL(7), or ORDERING_METIS (set before
      !! the first factorization).
      integer :: ordering = ORDERING_DEFAULT
      !> Smallest pattern the default ordering gives to METIS (see
      !! ORDERING_DEFAULT).
      integer :: metis_min_neq = METIS_MIN_NEQ
      !> CPU seconds of the last METIS ordering (0 when none ran).
      real(dp) :: ordering_seconds = 0.0_dp
      !> CPU seconds of the last analysis, ordering included.
      real(dp) :: analysis_seconds = 0.0_dp
      type(mumps_instance_t), private :: mumps
      integer, allocatable, private :: cp(:)          ! (0:neq) column pointers into IRN/JCN/A
      real(dp), allocatable, private :: base(:)       ! stored copy of K_AB
      integer, private :: analysis_count = 0
      integer, private :: ordering_used = -1
      integer, private :: nschur = 0                  ! Schur variables (0: none)
      logical, private :: analysed = .false.          ! MUMPS's analysis holds for the
                                                      ! pattern (and Schur variables)
      logical, private :: metis_missing = .false.     ! METIS asked for, not built in: AMD used
      logical, private :: many = .false.              ! many factorizations of the pattern expected
   contains
      procedure :: analyse => mumps_analyse
      procedure :: zero => mumps_zero
      procedure :: add_element => mumps_add_element
      procedure :: store_base => mumps_store_base
      procedure :: restore_base => mumps_restore_base
      procedure :: factorize => mumps_factorize
      procedure :: solve => mumps_solve
      procedure :: free => mumps_free
      procedure :: name => mumps_name
      procedure :: nnz => mumps_nnz
      procedure :: symbolic_analyses => mumps_symbolic_analyses
      procedure :: ordering_of_analysis => mumps_ordering_of_analysis
      procedure :: ordering_note => mumps_ordering_note
      procedure :: run_analysis => mumps_run_analysis
      procedure :: expect_refactorizations => mumps_expect_refactorizations
      procedure :: factorize_schur => mumps_factorize_schur
      procedure :: schur_condense => mumps_schur_condense
      procedure :: schur_expand => mumps_schur_expand
      ! bound so that gfortran keeps it for the submodules, which call it (a private module
      ! procedure that the module itself inlines everywhere is otherwise left out of the object)
      procedure, private :: update_memory
      final :: mumps_finalize
   end type mumps_solver_t

   interface
      !> Numerical factorization of the assembled values (the submodule's header says what
      !! fails and how).  A workspace error of MUMPS is retried with a doubled relaxation
      !! ICNTL(14), up to MAX_ATTEMPTS times.  (submodule mumps_solver_factorize)
      module subroutine mumps_factorize(this, status)
         class(mumps_solver_t), intent(inout) :: this
         type(status_t), intent(inout) :: status  !! set only on failure
      end subroutine mumps_factorize

      !> Factorize with the equations `vars` kept out of the elimination and return their
      !! dense Schur complement (submodule mumps_solver_schur, which says how).
      module subroutine mumps_factorize_schur(this, vars, s, status)
         class(mumps_solver_t), intent(inout) :: this
         integer, intent(in) :: vars(:)            !! the Schur variables (distinct equations)
         real(dp), intent(out) :: s(:, :)          !! (size(vars), size(vars)) the complement
         type(status_t), intent(inout) :: status   !! set only on failure
      end subroutine mumps_factorize_schur

      !> Condensation of a right-hand side onto the Schur variables (mumps_solver_schur).
      module subroutine mumps_schur_condense(this, b, g, status)
         class(mumps_solver_t), intent(inout) :: this
         real(dp), intent(in) :: b(:)              !! (neq) right-hand side
         real(dp), intent(out) :: g(:)             !! (n_c) reduced right-hand side
         type(status_t), intent(inout) :: status
      end subroutine mumps_schur_condense

      !> Expansion of a Schur solution to the whole solution (mumps_solver_schur).
      module subroutine mumps_schur_expand(this, xc, x, status)
         class(mumps_solver_t), intent(inout) :: this
         real(dp), intent(in) :: xc(:)             !! (n_c) solution at the Schur variables
         real(dp), intent(out) :: x(:)             !! (neq) the whole solution
         type(status_t), intent(inout) :: status
      end subroutine mumps_schur_expand
   end interface

contains

   !> Pattern of the upper triangle from the CSR equation graph, and MUMPS
   !! started on it; MUMPS's analysis follows at the first factorization
   !! (`run_analysis`).
   !!
   !! The graph may list each coupling once (either triangle) or twice.
   !! STAT_SOLVER for an invalid graph or when MUMPS cannot start.
   subroutine mumps_analyse(this, neq, xadj, adjncy, status)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(in) :: neq          !! number of equations
      integer, intent(in) :: xadj(:)      !! (neq+1) 1-based CSR row pointers of the graph
      integer, intent(in) :: adjncy(:)    !! columns coupled to each row, diagonal included
      type(status_t), intent(inout) :: status
      integer, allocatable :: rows(:)
      integer :: info1

      call this%free()
      call upper_pattern(neq, xadj, adjncy, this%cp, rows, status)
      if (.not. status%ok() .or. .not. allocated(rows)) return
      this%neq = neq
      this%stats%neq = neq
      this%stats%nnz_matrix = int(size(rows), i8)
      if (neq == 0) then
         this%state = ST_ASSEMBLING
         return
      end if

      call this%mumps%start(2, info1)
      if (info1 < 0) then
         call status%set(STAT_SOLVER, 'mumps solver: cannot start MUMPS: '// &
            mumps_error_text(info1, this%mumps%id%infog(2)))
         call this%free()
         return
      end if
      associate (id => this%mumps%id)
         id%n = neq
         id%nnz = int(size(rows), i8)
         allocate (id%irn(size(rows)), id%jcn(size(rows)), id%a(size(rows)), id%colsca(neq), &
            id%rhs(neq))
         id%rowsca => id%colsca          ! symmetric scaling: one array
                                         ! (Users' guide, ICNTL(8) = -1)
         call column_indices(this%cp, id%jcn)
         id%irn(:) = rows
         id%a(:) = 0.0_dp
         id%icntl(5) = 0                 ! assembled matrix
         id%icntl(18) = 0                ! centralized on the host
         id%icntl(6) = 0                 ! no matching: the analysis sees the pattern only
         id%icntl(8) = -1                ! scaling given by us: a unit diagonal
         id%icntl(12) = 1                ! plain ordering of the symmetric pattern
         id%icntl(13) = 1                ! root front not on ScaLAPACK:
                                         ! null pivots detected there too
         id%icntl(24) = 1                ! null pivot row detection ...
         id%cntl(3) = -this%pivot_tol    ! ... with an absolute threshold on the scaled matrix
         id%icntl(28) = 1                ! sequential analysis
      end associate
      this%analysed = .false.
      this%state = ST_ASSEMBLING
      call update_memory(this)
   end subroutine mumps_analyse

   !> MUMPS's analysis (JOB = 1) of the pattern, with the Schur variables of
   !! `factorize_schur` if any, in the ordering `ordering`; the first
   !! factorization runs it if it has not run.  STAT_SOLVER when it fails
   !! (MUMPS's reason).
   subroutine mumps_run_analysis(this, status)
      class(mumps_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status   !! set only on failure
      real(dp) :: t0, t1
      if (this%state == ST_EMPTY) then
         call status%set(STAT_SOLVER, 'mumps solver: run_analysis called before analyse')
         return
      end if
      if (this%neq == 0 .or. .not. this%mumps%started()) return
      call cpu_time(t0)
      associate (id => this%mumps%id)
         this%metis_missing = .false.
         this%ordering_seconds = 0.0_dp
         if (associated(id%perm_in)) deallocate (id%perm_in)
         if (effective_ordering(this) == ORDERING_METIS) then
            if (metis_available()) then
               allocate (id%perm_in(this%neq))
               call order_by_metis(this, id%perm_in, status)
               if (.not. status%ok()) return
               id%icntl(7) = 1
            else
               this%metis_missing = .true.
               id%icntl(7) = ORDERING_AMD
            end if
         else
            id%icntl(7) = effective_ordering(this)
         end if
         call this%mumps%run(JOB_ANALYSE)
         if (id%infog(1) < 0) then
            call status%set(STAT_SOLVER, 'mumps solver: analysis failed: '// &
               mumps_error_text(id%infog(1), id%infog(2)))
            return
         end if
         this%ordering_used = id%infog(7)
         if (this%ordering_used == 1 .and. effective_ordering(this) == ORDERING_METIS) then
            this%ordering_used = ORDERING_METIS
         end if
      end associate
      this%analysis_count = this%analysis_count + 1
      this%analysed = .true.
      call update_memory(this)
      call cpu_time(t1)
      this%analysis_seconds = t1 - t0
   end subroutine mumps_run_analysis

   !> The ordering the next analysis is to use (see `choose_ordering`).
   pure integer function effective_ordering(this) result(k)
      class(mumps_solver_t), intent(in) :: this
      k = choose_ordering(this%ordering, this%many, this%neq, this%metis_min_neq)
   end function effective_ordering

   !> Many factorizations of this pattern are to come (see ORDERING_DEFAULT).
   subroutine mumps_expect_refactorizations(this)
      class(mumps_solver_t), intent(inout) :: this
      this%many = .true.
      ! every factorization reuses the pages of the last (heap_policy)
      call keep_freed_heap()
   end subroutine mumps_expect_refactorizations

   !> PERM_IN from METIS (`metis_perm_in`), the Schur variables placed last; times the
   !! ordering (ordering_seconds).
   subroutine order_by_metis(this, perm_in, status)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(out) :: perm_in(:)        !! (neq)
      type(status_t), intent(inout) :: status
      real(dp) :: t0, t1
      call cpu_time(t0)
      if (this%nschur > 0) then
         call metis_perm_in(this%cp, this%mumps%id%irn, &
                            this%mumps%id%listvar_schur(1:this%nschur), perm_in, status)
      else
         call metis_perm_in(this%cp, this%mumps%id%irn, [integer ::], perm_in, status)
      end if
      if (.not. status%ok()) return
      call cpu_time(t1)
      this%ordering_seconds = t1 - t0
   end subroutine order_by_metis


   !> Memory held: MUMPS's own (INFOG(22) after a factorization, else the
   !! analysis estimate INFOG(17)), plus the pattern, values, stored copy,
   !! scaling and right-hand side arrays.
   subroutine update_memory(this)
      class(mumps_solver_t), intent(inout) :: this
      integer(i8) :: m, nnz
      m = 0
      if (allocated(this%cp)) m = m + 4_i8*size(this%cp, kind=i8)
      if (allocated(this%base)) m = m + 8_i8*size(this%base, kind=i8)
      if (this%mumps%started()) then
         nnz = this%mumps%id%nnz
         m = m + nnz*(4_i8 + 4_i8 + 8_i8) + 16_i8*this%neq
         ! the Schur complement, its variables and reduced right-hand side
         m = m + 8_i8*int(this%nschur, i8)**2 + 12_i8*this%nschur
         if (this%stats%factorizations > 0 .or. this%state == ST_FACTORED) then
            m = m + 1000000_i8*max(0, this%mumps%id%infog(22))
         else
            m = m + 1000000_i8*max(0, this%mumps%id%infog(17))
         end if
      end if
      this%stats%memory_bytes = m
   end subroutine update_memory

   !> Set every assembled value to zero (the pattern and the analysis stay).
   subroutine mumps_zero(this)
      class(mumps_solver_t), intent(inout) :: this
      if (this%state == ST_EMPTY) then
        call fatal_internal('mumps solver: zero called before analyse', 'mumps_solver.f90', &
           __LINE__)
      end if
      if (this%mumps%started()) this%mumps%id%a(:) = 0.0_dp
      this%n_outside = 0
      this%first_outside = 0
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine mumps_zero

   !> Scatter a symmetric element matrix into the upper triangle.
   !!
   !! The skyline rule: ke(a, b) with i = ieq(a) <= j = ieq(b) is added to
   !! K(i, j), so tied dofs sum onto the diagonal exactly as in the skyline
   !! solver.  Dofs with ieq <= 0 are skipped; a nonzero entry outside the
   !! pattern (or ieq > neq) is counted and reported by the next `factorize`.
   subroutine mumps_add_element(this, ieq, ke)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)       !! global equation of each element dof
      real(dp), intent(in) :: ke(:, :)    !! element matrix, size(ieq) square, symmetric
      integer :: ia, ib, i, j, nd, p

      call this%check_element(ieq, ke, 'mumps_solver.f90', __LINE__)
      nd = size(ieq)
      do ib = 1, nd
         j = ieq(ib)
         if (j <= 0) cycle
         do ia = 1, nd
            i = ieq(ia)
            if (i <= 0 .or. i > j) cycle
            p = 0
            if (j <= this%neq) p = locate_entry(this%cp, this%mumps%id%irn, i, j)
            if (p > 0) then
               this%mumps%id%a(p) = this%mumps%id%a(p) + ke(ia, ib)
            else if (.not. (abs(ke(ia, ib)) <= 0.0_dp)) then
               if (this%n_outside == 0) this%first_outside = [i, j]
               this%n_outside = this%n_outside + 1
            end if
         end do
      end do
   end subroutine mumps_add_element

   !> Keep a copy of the assembled values (K_AB) for `restore_base`.
   subroutine mumps_store_base(this)
      class(mumps_solver_t), intent(inout) :: this
      if (this%state /= ST_ASSEMBLING) call fatal_internal( &
         'mumps solver: store_base needs assembled values (call it before factorize)', &
         'mumps_solver.f90', __LINE__)
      if (this%mumps%started()) then
         this%base = this%mumps%id%a
      else
         allocate (this%base(0))
      end if
      this%base_outside = this%n_outside
      this%base_first_outside = this%first_outside
      call update_memory(this)
   end subroutine mumps_store_base

   !> Put back the values kept by `store_base` (the analysis is kept: the
   !! pattern has not changed).
   subroutine mumps_restore_base(this)
      class(mumps_solver_t), intent(inout) :: this
      if (.not. allocated(this%base) .or. this%state == ST_EMPTY) call fatal_internal( &
         'mumps solver: restore_base without store_base', 'mumps_solver.f90', __LINE__)
      if (this%mumps%started()) this%mumps%id%a(:) = this%base(:)
      this%n_outside = this%base_outside
      this%first_outside = this%base_first_outside
      this%bad_eq = 0
      this%state = ST_ASSEMBLING
   end subroutine mumps_restore_base


   !> Solve K x = b with the factors; b is overwritten with x, and left
   !! unchanged (status STAT_SOLVER) when there is no valid factorization or
   !! MUMPS's solve fails.
   subroutine mumps_solve(this, b, status)
      class(mumps_solver_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)          !! (neq) right-hand side in, solution out
      type(status_t), intent(inout) :: status  !! set only on failure

      if (.not. this%ready_to_solve(size(b), status)) return
      if (this%nschur > 0) then
         call status%set(STAT_SOLVER, &
            'mumps solver: the factorization holds a Schur complement: solve through '// &
            'schur_condense and schur_expand')
         return
      end if
      if (this%neq > 0) then
         associate (id => this%mumps%id)
            id%rhs(:) = b
            id%nrhs = 1
            id%lrhs = this%neq
            call this%mumps%run(JOB_SOLVE)
            if (id%infog(1) < 0) then
               call status%set(STAT_SOLVER, 'mumps solver: solve failed: '// &
                  mumps_error_text(id%infog(1), id%infog(2)))
               return
            end if
            b = id%rhs
         end associate
      end if
      this%stats%solves = this%stats%solves + 1
   end subroutine mumps_solve

   !> Release MUMPS's data and every array; the solver is as new.
   subroutine mumps_free(this)
      class(mumps_solver_t), intent(inout) :: this
      if (this%mumps%started()) then
         associate (id => this%mumps%id)
            if (associated(id%irn)) deallocate (id%irn)
            if (associated(id%jcn)) deallocate (id%jcn)
            if (associated(id%a)) deallocate (id%a)
            if (associated(id%colsca)) deallocate (id%colsca)
            if (associated(id%rhs)) deallocate (id%rhs)
            if (associated(id%listvar_schur)) deallocate (id%listvar_schur)
            if (associated(id%schur)) deallocate (id%schur)
            if (associated(id%redrhs)) deallocate (id%redrhs)
            if (associated(id%perm_in)) deallocate (id%perm_in)
            id%rowsca => null()
         end associate
         call this%mumps%finish()
      end if
      if (allocated(this%cp)) deallocate (this%cp)
      if (allocated(this%base)) deallocate (this%base)
      call this%reset_common()
      this%analysis_count = 0
      this%ordering_used = -1
      this%nschur = 0
      this%analysed = .false.
      this%metis_missing = .false.
      this%many = .false.
      this%ordering_seconds = 0.0_dp
   end subroutine mumps_free

   !> Release MUMPS's data when the solver goes out of scope.
   subroutine mumps_finalize(this)
      type(mumps_solver_t), intent(inout) :: this
      call mumps_free(this)
   end subroutine mumps_finalize

   function mumps_name(this) result(s)
      class(mumps_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      associate (unused => this)
      end associate
      s = 'mumps'
   end function mumps_name

   !> Entries of the pattern (upper triangle with the diagonal).
   pure integer(i8) function mumps_nnz(this) result(n)
      class(mumps_solver_t), intent(in) :: this
      n = 0
      if (allocated(this%cp)) n = int(this%cp(this%neq), i8)
   end function mumps_nnz

   !> MUMPS analyses done since the last `free` (1 per pattern).
   pure integer function mumps_symbolic_analyses(this) result(n)
      class(mumps_solver_t), intent(in) :: this
      n = this%analysis_count
   end function mumps_symbolic_analyses

   !> Ordering MUMPS used in the last analysis (INFOG(7): 0 AMD, 2 AMF,
   !! 3 SCOTCH, 4 PORD, 6 QAMD; ORDERING_METIS = 5 for METIS's given as the
   !! user ordering); -1 before an analysis (the first factorization).
   pure integer function mumps_ordering_of_analysis(this) result(n)
      class(mumps_solver_t), intent(in) :: this
      n = this%ordering_used
   end function mumps_ordering_of_analysis

   !> The ordering in words, for the listing: that of the last analysis, or
   !! before the first one the ordering it will use; it says when METIS was
   !! asked for and the build has none.  Empty before `analyse`.
   function mumps_ordering_note(this) result(s)
      class(mumps_solver_t), intent(in) :: this
      character(len=:), allocatable :: s
      integer :: k
      logical :: missing
      s = ''
      if (this%state == ST_EMPTY) return
      k = this%ordering_used
      missing = this%metis_missing
      if (.not. this%analysed) then
         k = effective_ordering(this)
         missing = k == ORDERING_METIS .and. .not. metis_available()
         if (missing) k = ORDERING_AMD
      end if
      s = ordering_text(k, missing)
   end function mumps_ordering_note

end module mumps_solver
