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
!! Ordering.  AMD (MUMPS's own, ICNTL(7) = 0), or METIS's nested dissection
!! given as a user ordering (ICNTL(7) = 1, PERM_IN from `metis_ordering`;
!! Debian's MUMPS is not linked with METIS), or MUMPS's SCOTCH and PORD.
!! With a Schur complement MUMPS ignores ICNTL(7) = 0, 3, 4 (it orders by
!! AMD) but takes a user ordering (INFOG(7) = 1 after the analysis, checked
!! by the unit tests).  The Schur variables are given the last places, in
!! their order (MUMPS keeps them out of the elimination: last is where they
!! belong), and METIS orders the graph of the other equations.  Without METIS in the build the METIS
!! ordering falls back to AMD (`ordering_note` says so).  Which ordering is
!! the default, and why, is said at ORDERING_DEFAULT.
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
   use sorting, only: insertion_sort
   use linear_solver, only: linear_solver_t, ST_EMPTY, ST_ASSEMBLING, ST_FACTORED, ST_FAILED
   use metis_ordering, only: metis_available, nested_dissection
   use mumps_instance, only: mumps_instance_t, mumps_error_text, mumps_size, JOB_ANALYSE, JOB_FACTORIZE, &
                             JOB_SOLVE
   implicit none
   private

   public :: mumps_solver_t
   public :: ORDERING_AMD, ORDERING_SCOTCH, ORDERING_PORD, ORDERING_AUTO, ORDERING_METIS, ORDERING_DEFAULT

   !> Fill-reducing orderings of MUMPS (ICNTL(7)).  AMD: deterministic and
   !! the cheapest analysis (0.3 s at 3e5 equations), the default for one
   !! factorization.  PORD stops the whole process (`exit`) on a graph it
   !! cannot split (a dense one: "no valid number of stages in
   !! multisector", met here on a 3-equation system), and SCOTCH's orderings
   !! differ from run to run (threads), so that results would not be
   !! bit-reproducible: both are available, never the default.
   integer, parameter :: ORDERING_AMD = 0, ORDERING_SCOTCH = 3, ORDERING_PORD = 4, ORDERING_AUTO = 7
   !> METIS's nested dissection (`metis_ordering`) given to MUMPS as a user
   !! ordering (ICNTL(7) = 1, PERM_IN); the value is MUMPS's INFOG(7) code
   !! for METIS.
   integer, parameter :: ORDERING_METIS = 5
   !> The default ordering (the value of `ordering` until it is set): AMD,
   !! but METIS when the pattern will be factorized many times
   !! (`expect_refactorizations`, the full contact system) and has at least
   !! METIS_MIN_NEQ equations.  METIS's analysis costs several times AMD's
   !! (1.5 s against 0.3 s at 3e5 equations) and saves 16-35 % of each
   !! factorization from 3e4 equations on: it pays back after 3 to 9
   !! factorizations, never in one (the Schur path, a model without contact).
   !! Measurements: docs/performance.md, "Orderings".
   integer, parameter :: ORDERING_DEFAULT = -1
   !> Smallest model ordered by METIS by default (below it the factorizations
   !! measured no faster with METIS).
   integer, parameter :: METIS_MIN_NEQ = 20000

   !> Workspace errors that a larger relaxation ICNTL(14) cures.
   integer, parameter :: WORKSPACE_ERRORS(4) = [-8, -9, -17, -20]
   !> Attempts of a factorization, doubling ICNTL(14) after each workspace error.
   integer, parameter :: MAX_ATTEMPTS = 4

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
      logical, private :: analysed = .false.          ! MUMPS's analysis holds for the pattern (and Schur variables)
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
      final :: mumps_finalize
   end type mumps_solver_t

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
         allocate (id%irn(size(rows)), id%jcn(size(rows)), id%a(size(rows)), id%colsca(neq), id%rhs(neq))
         id%rowsca => id%colsca          ! symmetric scaling: one array (Users' guide, ICNTL(8) = -1)
         call column_indices(this%cp, id%jcn)
         id%irn(:) = rows
         id%a(:) = 0.0_dp
         id%icntl(5) = 0                 ! assembled matrix
         id%icntl(18) = 0                ! centralized on the host
         id%icntl(6) = 0                 ! no matching: the analysis sees the pattern only
         id%icntl(8) = -1                ! scaling given by us: a unit diagonal
         id%icntl(12) = 1                ! plain ordering of the symmetric pattern
         id%icntl(13) = 1                ! root front not on ScaLAPACK: null pivots detected there too
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
               call metis_perm_in(this, id%perm_in, status)
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

   !> The ordering the next analysis is to use: `ordering`, or for the
   !! default METIS when many factorizations of a large enough pattern are
   !! expected, else AMD.  (METIS without METIS in the build: AMD, noted.)
   pure integer function effective_ordering(this) result(k)
      class(mumps_solver_t), intent(in) :: this
      k = this%ordering
      if (k /= ORDERING_DEFAULT) return
      k = ORDERING_AMD
      if (this%many .and. this%neq >= this%metis_min_neq) k = ORDERING_METIS
   end function effective_ordering

   !> Many factorizations of this pattern are to come (see ORDERING_DEFAULT).
   subroutine mumps_expect_refactorizations(this)
      class(mumps_solver_t), intent(inout) :: this
      this%many = .true.
   end subroutine mumps_expect_refactorizations

   !> PERM_IN (the place of every equation in the pivot order) from METIS's
   !! nested dissection: of the whole pattern, or, with Schur variables, of
   !! the pattern of the other equations, the Schur variables placed last in
   !! the order of LISTVAR_SCHUR (they are not eliminated).  Times the
   !! ordering (ordering_seconds).
   subroutine metis_perm_in(this, perm_in, status)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(out) :: perm_in(:)        !! (neq)
      type(status_t), intent(inout) :: status
      integer, allocatable :: sub(:), xadj(:), adjncy(:), place(:)
      integer :: n, nsub, i, j, p, k
      real(dp) :: t0, t1
      call cpu_time(t0)
      n = this%neq
      ! sub(i): the vertex of equation i in the graph METIS orders, 0 for a Schur variable
      allocate (sub(n))
      sub = 1
      if (this%nschur > 0) sub(this%mumps%id%listvar_schur(1:this%nschur)) = 0
      nsub = 0
      do i = 1, n
         if (sub(i) > 0) then
            nsub = nsub + 1
            sub(i) = nsub
         end if
      end do
      ! the graph of the upper pattern between such equations, both ends, no diagonal
      allocate (xadj(nsub + 1))
      xadj = 0
      do j = 1, n
         if (sub(j) == 0) cycle
         do p = this%cp(j - 1) + 1, this%cp(j)
            i = this%mumps%id%irn(p)
            if (i == j .or. sub(i) == 0) cycle
            xadj(sub(i) + 1) = xadj(sub(i) + 1) + 1
            xadj(sub(j) + 1) = xadj(sub(j) + 1) + 1
         end do
      end do
      xadj(1) = 1
      do k = 1, nsub
         xadj(k + 1) = xadj(k + 1) + xadj(k)
      end do
      allocate (adjncy(max(xadj(nsub + 1) - 1, 1)), place(nsub + 1))
      place(1:nsub) = xadj(1:nsub)
      do j = 1, n
         if (sub(j) == 0) cycle
         do p = this%cp(j - 1) + 1, this%cp(j)
            i = this%mumps%id%irn(p)
            if (i == j .or. sub(i) == 0) cycle
            adjncy(place(sub(i))) = sub(j)
            place(sub(i)) = place(sub(i)) + 1
            adjncy(place(sub(j))) = sub(i)
            place(sub(j)) = place(sub(j)) + 1
         end do
      end do
      call nested_dissection(nsub, xadj, adjncy, place, status)
      if (.not. status%ok()) then
         status%message = 'mumps solver: METIS ordering: '//status%message
         return
      end if
      do i = 1, n
         if (sub(i) > 0) perm_in(i) = place(sub(i))
      end do
      do k = 1, this%nschur
         perm_in(this%mumps%id%listvar_schur(k)) = nsub + k
      end do
      call cpu_time(t1)
      this%ordering_seconds = t1 - t0
   end subroutine metis_perm_in

   !> Upper-triangle pattern (column pointers, sorted rows, diagonal last)
   !! of a CSR equation graph; checks the graph.
   subroutine upper_pattern(neq, xadj, adjncy, cp, rows, status)
      integer, intent(in) :: neq, xadj(:), adjncy(:)
      integer, allocatable, intent(out) :: cp(:)     !! (0:neq) column pointers
      integer, allocatable, intent(out) :: rows(:)   !! (cp(neq)) rows of each column
      type(status_t), intent(inout) :: status
      integer, allocatable :: cnt(:), pos(:)
      integer :: r, c, p, j, k, q, last, ierr
      integer(i8) :: nnz8

      if (neq < 0) then
         call status%set(STAT_SOLVER, 'mumps solver: negative number of equations '//itoa(neq))
         return
      end if
      if (neq > 0) then
         if (size(xadj) < neq + 1) then
            call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (xadj has '// &
                            itoa(size(xadj))//' entries, needs '//itoa(neq + 1)//')')
            return
         end if
         if (xadj(1) /= 1 .or. xadj(neq + 1) - 1 > size(adjncy)) then
            call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (xadj must start at 1 '// &
                            'and end within adjncy)')
            return
         end if
      end if
      allocate (cnt(max(neq, 1)))
      cnt = 1
      do r = 1, neq
         if (xadj(r + 1) < xadj(r)) then
            call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (xadj decreases at row '// &
                            itoa(r)//')')
            return
         end if
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c < 1 .or. c > neq) then
               call status%set(STAT_SOLVER, 'mumps solver: invalid equation graph (row '//itoa(r)// &
                               ' lists equation '//itoa(c)//')')
               return
            end if
            if (c /= r) cnt(max(r, c)) = cnt(max(r, c)) + 1
         end do
      end do
      nnz8 = sum(int(cnt(1:neq), i8))
      if (nnz8 >= int(huge(1), i8)) then
         call status%set(STAT_SOLVER, 'mumps solver: '//itoa(neq)//' equations give more than 2^31 '// &
                         'matrix entries')
         return
      end if
      allocate (cp(0:neq), pos(max(neq, 1)), stat=ierr)
      if (ierr == 0) allocate (rows(nnz8), stat=ierr)
      if (ierr /= 0) then
         call status%set(STAT_SOLVER, 'mumps solver: cannot allocate a pattern of '//itoa(int(nnz8))//' entries')
         return
      end if
      cp(0) = 0
      do j = 1, neq
         cp(j) = cp(j - 1) + cnt(j)
         pos(j) = cp(j - 1) + 1
      end do
      do r = 1, neq
         do p = xadj(r), xadj(r + 1) - 1
            c = adjncy(p)
            if (c == r) cycle
            j = max(r, c)
            rows(pos(j)) = min(r, c)
            pos(j) = pos(j) + 1
         end do
      end do
      do j = 1, neq
         rows(pos(j)) = j             ! the diagonal, the largest row of its column
      end do
      ! sort every column and drop duplicates (a coupling listed twice)
      q = 0
      last = 0
      do j = 1, neq
         k = cp(j - 1) + 1
         call insertion_sort(rows(k:cp(j)))
         do p = k, cp(j)
            if (p > k) then
               if (rows(p) == rows(p - 1)) cycle
            end if
            q = q + 1
            rows(q) = rows(p)
         end do
         cp(j - 1) = last
         last = q
      end do
      cp(neq) = q
      if (q < size(rows)) rows = rows(1:q)
   end subroutine upper_pattern

   !> Column index of every entry from the column pointers.
   pure subroutine column_indices(cp, jcn)
      integer, intent(in) :: cp(0:)
      integer, intent(out) :: jcn(:)
      integer :: j
      do j = 1, ubound(cp, 1)
         jcn(cp(j - 1) + 1:cp(j)) = j
      end do
   end subroutine column_indices

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
        call fatal_internal('mumps solver: zero called before analyse', 'mumps_solver.f90', __LINE__)
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
            if (j <= this%neq) p = locate(this, i, j)
            if (p > 0) then
               this%mumps%id%a(p) = this%mumps%id%a(p) + ke(ia, ib)
            else if (.not. (abs(ke(ia, ib)) <= 0.0_dp)) then
               if (this%n_outside == 0) this%first_outside = [i, j]
               this%n_outside = this%n_outside + 1
            end if
         end do
      end do
   end subroutine mumps_add_element

   !> Position of entry (i, j), i <= j, in IRN/JCN/A; 0 if the pattern does
   !! not hold it.  Binary search of column j's sorted rows.
   pure integer function locate(this, i, j) result(p)
      class(mumps_solver_t), intent(in) :: this
      integer, intent(in) :: i, j
      integer :: lo, hi, mid
      lo = this%cp(j - 1) + 1
      hi = this%cp(j)
      p = 0
      do while (lo <= hi)
         mid = (lo + hi)/2
         if (this%mumps%id%irn(mid) == i) then
            p = mid
            return
         else if (this%mumps%id%irn(mid) < i) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
   end function locate

   !> Keep a copy of the assembled values (K_AB) for `restore_base`.
   subroutine mumps_store_base(this)
      class(mumps_solver_t), intent(inout) :: this
      if (this%state /= ST_ASSEMBLING) call fatal_internal( &
         'mumps solver: store_base needs assembled values (call it before factorize)', 'mumps_solver.f90', __LINE__)
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

   !> Numerical factorization of the assembled values (see the module header
   !! for what fails and how).  A workspace error of MUMPS is retried with a
   !! doubled relaxation ICNTL(14), up to MAX_ATTEMPTS times.
   subroutine mumps_factorize(this, status)
      class(mumps_solver_t), intent(inout) :: this
      type(status_t), intent(inout) :: status  !! set only on failure
      integer :: attempt, j, jbad

      select case (this%state)
      case (ST_EMPTY)
         call status%set(STAT_SOLVER, 'mumps solver: factorize called before analyse')
         return
      case (ST_FACTORED, ST_FAILED)
         call status%set(STAT_SOLVER, 'mumps solver: factorize called twice on the same '// &
                         'values (call restore_base or zero and assemble again)')
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
            call fail(this, status, STAT_SOLVER, 'mumps solver: the assembled matrix holds NaN or Inf', 0)
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
            call fail(this, status, STAT_SINGULAR, 'singular or unrestrained model: zero or negative '// &
                      'pivot at equation '//itoa(jbad)//' (diagonal = '//rtoa(id%a(this%cp(jbad)))// &
                      ', a positive definite matrix has none)', jbad)
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
            call fail(this, status, STAT_SINGULAR, 'singular or unrestrained model: zero pivot at equation '// &
                      itoa(j)//' (MUMPS: '//itoa(id%infog(28))//' null pivot row(s), no entry above '// &
                      rtoa(this%pivot_tol)//' of the diagonal)', j)
            return
         end if
         if (id%infog(12) > 0) then
            call fail(this, status, STAT_SINGULAR, 'singular or unrestrained model: the matrix is not '// &
                      'positive definite (MUMPS: '//itoa(id%infog(12))//' negative pivot(s)); the equation '// &
                      'cannot be told', 0)
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

   !> Solve K x = b with the factors; b is overwritten with x, and left
   !! unchanged (status STAT_SOLVER) when there is no valid factorization or
   !! MUMPS's solve fails.
   subroutine mumps_solve(this, b, status)
      class(mumps_solver_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)          !! (neq) right-hand side in, solution out
      type(status_t), intent(inout) :: status  !! set only on failure

      if (.not. this%ready_to_solve(size(b), status)) return
      if (this%nschur > 0) then
         call status%set(STAT_SOLVER, 'mumps solver: the factorization holds a Schur complement: '// &
                         'solve through schur_condense and schur_expand')
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
      select case (k)
      case (ORDERING_AMD)
         s = 'AMD ordering'
      case (ORDERING_METIS)
         s = 'METIS nested-dissection ordering'
      case (ORDERING_SCOTCH)
         s = 'SCOTCH ordering'
      case (ORDERING_PORD)
         s = 'PORD ordering'
      case default
         s = 'MUMPS ordering '//itoa(k)
      end select
      if (missing) s = s//' (METIS would be used: this build has no METIS)'
   end function mumps_ordering_note

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
   subroutine mumps_factorize_schur(this, vars, s, status)
      class(mumps_solver_t), intent(inout) :: this
      integer, intent(in) :: vars(:)            !! the Schur variables (distinct equations)
      real(dp), intent(out) :: s(:, :)          !! (size(vars), size(vars)) the Schur complement
      type(status_t), intent(inout) :: status   !! set only on failure
      integer :: nc, i, j
      real(dp) :: di, dj
      nc = size(vars)
      if (this%state /= ST_ASSEMBLING .or. .not. this%mumps%started()) then
         call status%set(STAT_SOLVER, 'mumps solver: factorize_schur needs assembled values (restore_base first)')
         return
      end if
      if (nc < 1 .or. nc >= this%neq .or. any(vars < 1 .or. vars > this%neq)) then
         call status%set(STAT_SOLVER, 'mumps solver: invalid Schur variables (need 1 to neq-1 equations '// &
                         'within 1..'//itoa(this%neq)//')')
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
   subroutine mumps_schur_condense(this, b, g, status)
      class(mumps_solver_t), intent(inout) :: this
      real(dp), intent(in) :: b(:)              !! (neq) right-hand side
      real(dp), intent(out) :: g(:)             !! (n_c) reduced right-hand side, in the order of vars
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
            call status%set(STAT_SOLVER, 'mumps solver: condensation of a right-hand side failed: '// &
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
   subroutine mumps_schur_expand(this, xc, x, status)
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
      if (.not. ok) call status%set(STAT_SOLVER, 'mumps solver: no Schur complement of '//itoa(nc)// &
                                    ' variables to condense onto (factorize_schur first)')
   end function schur_ready
end module mumps_solver
