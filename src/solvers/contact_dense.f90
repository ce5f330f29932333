!> The dense system of the contact equations, shared by the systems that
!! condense the bodies onto them (condensed_system, mumps_schur_system).
!!
!! With the bodies' stiffness condensed onto the n_c contact equations, S
!! (symmetric, n_c x n_c), every set of springs gives the dense system
!!
!!     (S + K_c) x_c = g
!!
!! where K_c, assembled pair by pair, has at most 2 nn entries a column.  An
!! increment therefore costs: a copy of S, the springs added entry by entry
!! (no product with S or with the bodies' coupling), one dense factorization,
!! and per right-hand side two triangular solves, all in LAPACK (OpenBLAS or
!! the reference BLAS, whichever the system's alternatives give).
!!
!! The factorization is a Cholesky factorization (dpotrf) when S + K_c is
!! positive definite, which it is whenever the model is restrained: the
!! Schur complement of a positive definite matrix is positive definite, and
!! positive springs keep it so.  A pivot of the Cholesky factor with
!! l_kk^2 <= 1e-12 a_kk (the skyline solver's relative test d_k <= tol k_kk
!! for LDL^T) marks a singular system -- a body whose springs all opened, say
!! -- and names its contact equation.  When dpotrf finds the matrix not
!! positive definite, the system is factorized again by LU with partial
!! pivoting (dgetrf), with the singular-pivot test of the former condensation
!! (|u_kk| <= 1e-12 of the column's largest entry), so that an indefinite but
!! regular system still solves.  dpotrf writes the upper triangle only: the
!! strictly lower triangle and the saved diagonal still hold the matrix for
!! the LU, without a second copy.
!!
!! Low-rank updates.  Between two sets of springs only the pairs whose
!! modes changed differ, usually a few: with U the unit columns of the m
!! contact equations of those pairs and D (m x m) their change of springs
!! since the last factorization of A_0 = S + K_c,0, the new system is
!! A_0 + U D U^T and (Sherman-Morrison-Woodbury, without inverting D)
!!
!!     x = y - Z t,  y = A_0^-1 g,  Z = A_0^-1 U,  (I + D Z_p) t = D y_p
!!
!! (subscript p: the rows of the m equations).  Z costs 2 n^2 m flops
!! against n^3/3 for a new Cholesky factorization, so the factors of A_0 are
!! kept while m <= n/8 (`lowrank_max`) and refactorized beyond, or when the
!! small system I + D Z_p has a pivot below 1e-8 of its column (a change close
!! to singular is decided by the factorization and its pivot test above).
!! Systems below `lowrank_min_n` equations always refactorize.
!!
!! The springs' own coordinates.  A pair's springs act on the relative
!! displacement of its nodes (rank 2): once `prepare_projection` has the
!! reference springs, a set of springs in their range is factorized in those
!! coordinates (contact_projection: a Cholesky factorization of about n_c/2
!! equations, 8 times fewer flops), any other directly as above; a singular
!! system is always decided, and its equation named, by the direct
!! factorization.  A solution through Woodbury's identity is refined against
!! S + K_c itself (dense_solve), except in the springs' coordinates for
!! symmetric springs no stiffer than NO_REFINE_STIFFNESS times the reference
!! springs, where the identity loses no more than that factor of digits.
!!
!! No allocation happens after `init` and `prepare_projection`.
!! Ref: G. H. Golub, C. F. Van Loan, Matrix Computations, 4th ed. (2013),
!!      sec. 4.2 (Cholesky), 3.4 (LU with partial pivoting); LAPACK Users'
!!      Guide, 3rd ed. (1999), dpotrf/dpotrs, dgetrf/dgetrs; W. W. Hager,
!!      "Updating the inverse of a matrix", SIAM Review 31 (1989) 221-239.
module contact_dense
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SOLVER, STAT_SINGULAR
   use strings, only: itoa
   use contact_projection, only: contact_projection_t
   use lapack_interfaces, only: dpotrf, dpotrs, dgetrf, dgetrs, dsymv, dgemv, dtrsv
   implicit none
   private
   public :: contact_dense_t, PIVOT_TOL, set_contact_springs

   !> Relative pivot threshold of a singular system (the skyline solver's).
   real(dp), parameter :: PIVOT_TOL = 1.0e-12_dp
   !> Relative pivot threshold of the small system of a low-rank update,
   !! below which the system is refactorized instead.
   real(dp), parameter :: LOWRANK_TOL = 1.0e-8_dp
   !> Iterative refinement of a solution through Woodbury's identity: until
   !! the correction is below REFINE_TOL of the solution, at most MAX_REFINE
   !! steps (else the direct factorization).
   real(dp), parameter :: REFINE_TOL = 1.0e-12_dp
   integer, parameter :: MAX_REFINE = 3
   !> A solution in the springs' coordinates is not refined when the springs
   !! are symmetric and no stiffer than this many times the reference springs
   !! (about the bodies' own stiffness, K_ref being 0.1 of their diagonal):
   !! Woodbury's x = y - V (t - z) then loses at most about that factor times
   !! the round-off of a direct solve (see contact_projection), as the
   !! refinement step it would cost confirms.
   real(dp), parameter :: NO_REFINE_STIFFNESS = 10.0_dp

   !> S, and the factors of S + K_c.
   type :: contact_dense_t
      integer :: n = 0                       !! contact equations
      real(dp), allocatable :: s(:, :)       !! the bodies condensed onto them (symmetric)
      real(dp), allocatable :: a(:, :)       !! S + K_c, then its factors
      real(dp), allocatable :: diag(:)       !! diagonal of S + K_c before the factorization
      real(dp), allocatable :: rhs(:, :)     !! (n, 1) right-hand side of LAPACK's solves
      integer, allocatable :: ipiv(:)        !! LU pivots
      logical :: cholesky = .true.           !! the factors are Cholesky's (else LU's)
      logical :: factored = .false.          !! the factors are valid
      integer :: bad = 0                     !! index of a singular pivot (0: none)
      ! low-rank updates of the factors of A_0 = S + K_c,0
      integer :: lowrank_min_n = 64          !! smaller systems always refactorize
      integer :: lowrank_max = 0             !! most equations of an update (n/8)
      integer :: m = 0                       !! equations of the current update (0: none)
      integer :: factorizations = 0          !! dense factorizations so far
      integer :: updates = 0                 !! low-rank updates so far
      real(dp), allocatable :: kc0(:, :, :)  !! (nd, nd, npair) springs of A_0
      integer, allocatable :: plist(:)       !! (lowrank_max) positions of the update
      integer, allocatable :: mark(:)        !! (n) index of a position in plist, 0 if none
      real(dp), allocatable :: z(:, :)       !! (n, lowrank_max) A_0^-1 U
      real(dp), allocatable :: d(:, :)       !! (lowrank_max, lowrank_max) change of springs D
      real(dp), allocatable :: mm(:, :)      !! (lowrank_max, lowrank_max) I + D Z_p, LU factors
      integer, allocatable :: mpiv(:)        !! its pivots
      real(dp), allocatable :: t(:)          !! (lowrank_max) work
      ! the springs' own coordinates (contact_projection), when prepared
      type(contact_projection_t) :: proj     !! S's fixed matrices in them
      logical :: projected = .false.         !! the current springs are factorized there
      integer, allocatable :: ppos(:, :)     !! (nd, npair) positions of the pairs' dofs
      real(dp), allocatable :: kcur(:, :, :) !! (nd, nd, npair) the current springs
      real(dp), allocatable :: g0(:), r(:)   !! (n) right-hand side and residual of a refinement
      integer :: refinements = 0             !! refinement steps so far
      integer :: fallbacks = 0               !! refinements that gave up for
                                             !! the direct factorization
   contains
      procedure :: init => dense_init
      procedure :: prepare_projection => dense_prepare_projection
      procedure :: set_springs => dense_set_springs
      procedure :: solve => dense_solve
      procedure :: memory_bytes => dense_memory
      procedure, private :: begin_springs => dense_begin_springs
      procedure, private :: add_spring => dense_add_spring
      procedure, private :: factorize => dense_factorize
      procedure, private :: low_rank => dense_low_rank
      procedure, private :: woodbury_solve => dense_woodbury_solve
      procedure, private :: base_solve => dense_base_solve
      procedure, private :: residual => dense_residual
      procedure, private :: direct => dense_direct
   end type contact_dense_t

contains

   !> Storage for n contact equations and the springs of npair pairs of nd
   !! dofs; S is then set by the caller (this%s).
   subroutine dense_init(this, n, nd, npair)
      class(contact_dense_t), intent(inout) :: this
      integer, intent(in) :: n, nd, npair
      integer :: q
      this%n = n
      if (allocated(this%s)) deallocate (this%s, this%a, this%diag, this%rhs, this%ipiv, &
                                         this%kc0, this%plist, &
                                         this%mark, this%z, this%d, this%mm, this%mpiv, this%t, &
                                         this%ppos, &
                                         this%kcur, this%g0, this%r)
      q = max(1, n/8)
      this%lowrank_max = q
      allocate (this%s(n, n), this%a(n, n), this%diag(n), this%rhs(n, 1), this%ipiv(n), &
                this%kc0(nd, nd, npair), &
                this%plist(q), this%mark(n), this%z(n, q), this%d(q, q), this%mm(q, q), &
                this%mpiv(q), this%t(q), &
                this%ppos(nd, npair), this%kcur(nd, nd, npair), this%g0(n), this%r(n))
      this%ppos = 0
      this%kcur = 0.0_dp
      this%s = 0.0_dp
      this%kc0 = 0.0_dp
      this%mark = 0
      this%factored = .false.
      this%bad = 0
      this%m = 0
      this%factorizations = 0
      this%updates = 0
   end subroutine dense_init

   !> Prepare the springs' own coordinates (contact_projection) once S is
   !! set: from then on a set of springs in the range of the reference
   !! springs kref is factorized there, any other directly.
   subroutine dense_prepare_projection(this, ppos, kref)
      class(contact_dense_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)          !! (nd, npair) positions of the pairs' dofs
      real(dp), intent(in) :: kref(:, :, :)      !! (nd, nd, npair) reference springs
      this%ppos = ppos
      if (this%n > 0) call this%proj%setup(this%s, ppos, kref)
   end subroutine dense_prepare_projection

   !> The system S + K_c of the springs kc (pair by pair, ppos: positions of
   !! the pairs' dofs, <= 0 none): a low-rank update of the last factors when
   !! few pairs changed, else a new factorization.  A singular system gives
   !! `bad` > 0, the index of its pivot (the caller names the equation).
   subroutine dense_set_springs(this, ppos, kc, status)
      class(contact_dense_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)           !! (nd, npair)
      real(dp), intent(in) :: kc(:, :, :)         !! (nd, nd, npair)
      type(status_t), intent(inout) :: status
      logical :: done
      this%bad = 0
      this%projected = .false.
      this%ppos = ppos
      this%kcur = kc
      if (this%proj%ready) then
         call this%proj%set_springs(ppos, kc, this%projected)
         if (this%projected) return
      end if
      if (this%factored .and. this%n >= this%lowrank_min_n) then
         call this%low_rank(ppos, kc, done, status)
         if (done .or. .not. status%ok()) return
      end if
      call this%direct(status)
   end subroutine dense_set_springs

   !> The springs kc as a low-rank update of the factors of A_0 (see the
   !! module header); done = .false. when a new factorization is due.
   subroutine dense_low_rank(this, ppos, kc, done, status)
      class(contact_dense_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(in) :: kc(:, :, :)
      logical, intent(out) :: done
      type(status_t), intent(inout) :: status
      integer :: j, k, l, p, m, info
      real(dp) :: cmax
      done = .false.
      ! the positions of the pairs whose springs changed since A_0
      m = 0
      pairs: do j = 1, size(ppos, 2)
         if (all(abs(kc(:, :, j) - this%kc0(:, :, j)) <= 0.0_dp)) cycle pairs
         do k = 1, size(ppos, 1)
            p = ppos(k, j)
            if (p <= 0) cycle
            if (this%mark(p) > 0) cycle
            m = m + 1
            if (m > this%lowrank_max) exit pairs
            this%plist(m) = p
            this%mark(p) = m
         end do
      end do pairs
      do k = 1, min(m, this%lowrank_max)
         this%mark(this%plist(k)) = 0
      end do
      if (m > this%lowrank_max) return
      this%m = m
      done = .true.
      if (m == 0) return
      do k = 1, m
         this%mark(this%plist(k)) = k
      end do
      ! D: the change of springs on the m positions
      this%d(1:m, 1:m) = 0.0_dp
      do j = 1, size(ppos, 2)
         if (all(abs(kc(:, :, j) - this%kc0(:, :, j)) <= 0.0_dp)) cycle
         do l = 1, size(ppos, 1)
            if (ppos(l, j) <= 0) cycle
            do k = 1, size(ppos, 1)
               if (ppos(k, j) <= 0) cycle
               this%d(this%mark(ppos(k, j)), this%mark(ppos(l, j))) = &
                     this%d(this%mark(ppos(k, j)), &
                  this%mark(ppos(l, j))) + (kc(k, l, j) - this%kc0(k, l, j))
            end do
         end do
      end do
      do k = 1, m
         this%mark(this%plist(k)) = 0
      end do
      ! Z = A_0^-1 U
      this%z(:, 1:m) = 0.0_dp
      do k = 1, m
         this%z(this%plist(k), k) = 1.0_dp
      end do
      if (this%cholesky) then
         call dpotrs('U', this%n, m, this%a, this%n, this%z, this%n, info)
      else
         call dgetrs('N', this%n, m, this%a, this%n, this%ipiv, this%z, this%n, info)
      end if
      if (info /= 0) then
         call status%set(STAT_SOLVER, &
                         'LAPACK solve of the contact equations: illegal argument '//itoa(-info))
         return
      end if
      ! I + D Z_p, by LU; a small pivot: refactorize instead
      do l = 1, m
         do k = 1, m
            this%mm(k, l) = 0.0_dp
            do j = 1, m
               this%mm(k, l) = this%mm(k, l) + this%d(k, j)*this%z(this%plist(j), l)
            end do
         end do
         this%mm(l, l) = this%mm(l, l) + 1.0_dp
      end do
      do l = 1, m
         this%t(l) = maxval(abs(this%mm(1:m, l)))
      end do
      call dgetrf(m, m, this%mm, size(this%mm, 1), this%mpiv, info)
      if (info < 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrf: illegal argument '//itoa(-info))
         return
      end if
      do l = 1, m
         cmax = this%t(l)
         if (.not. abs(this%mm(l, l)) > LOWRANK_TOL*cmax) then
            done = .false.
            this%m = 0
            return
         end if
      end do
      this%updates = this%updates + 1
   end subroutine dense_low_rank

   !> Start a new set of springs: a = S.
   subroutine dense_begin_springs(this)
      class(contact_dense_t), intent(inout) :: this
      this%a = this%s
      this%factored = .false.
   end subroutine dense_begin_springs

   !> Add a spring matrix ke at the positions ipos of its dofs (<= 0: skipped).
   pure subroutine dense_add_spring(this, ipos, ke)
      class(contact_dense_t), intent(inout) :: this
      integer, intent(in) :: ipos(:)
      real(dp), intent(in) :: ke(:, :)
      integer :: i, j
      do j = 1, size(ipos)
         if (ipos(j) <= 0) cycle
         do i = 1, size(ipos)
            if (ipos(i) <= 0) cycle
            this%a(ipos(i), ipos(j)) = this%a(ipos(i), ipos(j)) + ke(i, j)
         end do
      end do
   end subroutine dense_add_spring

   !> Factorize S + K_c: Cholesky, or LU when it is not positive definite.
   !! A singular system gives STAT_SINGULAR with the index of its pivot in
   !! `bad` (the caller names the equation).
   subroutine dense_factorize(this, status)
      class(contact_dense_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer :: info, k, j
      real(dp) :: cmax
      this%bad = 0
      this%factored = .false.
      if (this%n == 0) then
         this%factored = .true.
         return
      end if
      do k = 1, this%n
         this%diag(k) = this%a(k, k)
      end do
      call dpotrf('U', this%n, this%a, this%n, info)
      if (info < 0) then
         call status%set(STAT_SOLVER, 'LAPACK dpotrf: illegal argument '//itoa(-info))
         return
      end if
      if (info == 0) then
         this%cholesky = .true.
         do k = 1, this%n
            if (this%a(k, k)**2 <= PIVOT_TOL*this%diag(k)) then
               this%bad = k
               return
            end if
         end do
         this%factored = .true.
         return
      end if
      ! not positive definite: the matrix again from its lower triangle and
      ! diagonal, then LU
      this%cholesky = .false.
      do j = 1, this%n
         this%a(j, j) = this%diag(j)
         do k = j + 1, this%n
            this%a(j, k) = this%a(k, j)
         end do
      end do
      ! the column maxima of the matrix go to diag (the pivot test's scale)
      do k = 1, this%n
         cmax = 0.0_dp
         do j = 1, this%n
            cmax = max(cmax, abs(this%a(j, k)))
         end do
         this%diag(k) = cmax
      end do
      call dgetrf(this%n, this%n, this%a, this%n, this%ipiv, info)
      if (info < 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrf: illegal argument '//itoa(-info))
         return
      end if
      do k = 1, this%n
         if (abs(this%a(k, k)) <= PIVOT_TOL*this%diag(k)) then
            this%bad = k
            return
         end if
      end do
      this%factored = .true.
   end subroutine dense_factorize

   !> x = (S + K_c)^-1 x with the factors (x overwritten).  A solution
   !! through Woodbury's identity (a low-rank update, or the springs'
   !! coordinates) is refined against S + K_c itself until the correction is
   !! below REFINE_TOL of it; if it is not after MAX_REFINE steps, the springs
   !! are factorized directly and the solve repeated (a singular system then
   !! gives `bad` > 0 for the caller to report, as from set_springs).
   subroutine dense_solve(this, x, status)
      class(contact_dense_t), intent(inout) :: this
      real(dp), intent(inout) :: x(:)            !! (n)
      type(status_t), intent(inout) :: status
      integer :: it
      logical :: ok
      this%bad = 0
      if (this%n == 0) return
      if (this%projected .or. this%m > 0) then
         this%g0 = x
         call this%woodbury_solve(x, ok, status)
         if (.not. status%ok()) return
         if (ok .and. this%projected) then
            if (this%proj%symmetric .and. this%proj%stiffness <= NO_REFINE_STIFFNESS) return
         end if
         if (ok) then
            do it = 1, MAX_REFINE
               call this%residual(x, this%r)
               call this%woodbury_solve(this%r, ok, status)
               if (.not. status%ok()) return
               if (.not. ok) exit
               x = x + this%r
               this%refinements = this%refinements + 1
               if (maxval(abs(this%r)) <= REFINE_TOL*maxval(abs(x))) return
            end do
         end if
         ! not converging, or the springs not positive definite in their
         ! coordinates: the direct factorization of these springs
         this%fallbacks = this%fallbacks + 1
         call this%direct(status)
         if (.not. status%ok() .or. this%bad > 0) return
         x = this%g0
      end if
      call this%base_solve(x, status)
   end subroutine dense_solve

   !> Solve with the factors of A_0 and the low-rank update, or in the
   !! springs' coordinates (ok = .false.: the springs are not clearly
   !! positive definite there, x undefined).
   subroutine dense_woodbury_solve(this, x, ok, status)
      class(contact_dense_t), intent(inout) :: this
      real(dp), intent(inout) :: x(:)
      logical, intent(out) :: ok
      type(status_t), intent(inout) :: status
      integer :: info, m, j, k
      ok = .true.
      if (this%projected) then
         call this%proj%solve(this%ppos, x, ok)
         return
      end if
      call this%base_solve(x, status)
      if (.not. status%ok()) return
      ! the low-rank update: x = y - Z t, (I + D Z_p) t = D y_p
      m = this%m
      do k = 1, m
         this%t(k) = 0.0_dp
         do j = 1, m
            this%t(k) = this%t(k) + this%d(k, j)*x(this%plist(j))
         end do
      end do
      call dgetrs('N', m, 1, this%mm, size(this%mm, 1), this%mpiv, this%t, m, info)
      call dgemv('N', this%n, m, -1.0_dp, this%z, this%n, this%t, 1, 1.0_dp, x, 1)
   end subroutine dense_woodbury_solve

   !> Solve with the factors of the last direct factorization (A_0).
   subroutine dense_base_solve(this, x, status)
      class(contact_dense_t), intent(inout) :: this
      real(dp), intent(inout) :: x(:)
      type(status_t), intent(inout) :: status
      integer :: info
      if (.not. this%factored) then
         call status%set(STAT_SOLVER, &
                         'contact system: solve without valid factors of the contact equations')
         return
      end if
      if (this%cholesky) then
         call dtrsv('U', 'T', 'N', this%n, this%a, this%n, x, 1)
         call dtrsv('U', 'N', 'N', this%n, this%a, this%n, x, 1)
         return
      end if
      this%rhs(:, 1) = x
      call dgetrs('N', this%n, 1, this%a, this%n, this%ipiv, this%rhs, this%n, info)
      if (info /= 0) then
         call status%set(STAT_SOLVER, &
                         'LAPACK solve of the contact equations: illegal argument '//itoa(-info))
         return
      end if
      x = this%rhs(:, 1)
   end subroutine dense_base_solve

   !> r = g0 - (S + K_c) x for the current springs.
   subroutine dense_residual(this, x, r)
      class(contact_dense_t), intent(inout) :: this
      real(dp), intent(in) :: x(:)
      real(dp), intent(out) :: r(:)
      integer :: j, a, b
      call dsymv('U', this%n, -1.0_dp, this%s, this%n, x, 1, 0.0_dp, r, 1)
      r = r + this%g0
      do j = 1, size(this%ppos, 2)
         do b = 1, size(this%ppos, 1)
            if (this%ppos(b, j) <= 0) cycle
            do a = 1, size(this%ppos, 1)
               if (this%ppos(a, j) <= 0) cycle
               r(this%ppos(a, j)) = r(this%ppos(a, j)) - this%kcur(a, b, j)*x(this%ppos(b, j))
            end do
         end do
      end do
   end subroutine dense_residual

   !> The direct factorization of S + the current springs.
   subroutine dense_direct(this, status)
      class(contact_dense_t), intent(inout) :: this
      type(status_t), intent(inout) :: status
      integer :: j
      this%projected = .false.
      call this%begin_springs()
      do j = 1, size(this%ppos, 2)
         call this%add_spring(this%ppos(:, j), this%kcur(:, :, j))
      end do
      call this%factorize(status)
      this%kc0 = this%kcur
      this%m = 0
      this%factorizations = this%factorizations + 1
   end subroutine dense_direct

   !> S, the factors, and the vectors [bytes].
   pure integer(i8) function dense_memory(this) result(bytes)
      class(contact_dense_t), intent(in) :: this
      integer(i8) :: n, q
      n = int(this%n, i8)
      q = int(this%lowrank_max, i8)
      bytes = 8_i8*(2_i8*n*n + 2_i8*n + n*q + 2_i8*q*q + q) + 4_i8*(2_i8*n + 2_i8*q)
      if (allocated(this%kc0)) bytes = bytes + 8_i8*size(this%kc0, kind=i8)
      if (allocated(this%kcur)) bytes = bytes + 8_i8*size(this%kcur, kind=i8) + 16_i8*n
      bytes = bytes + this%proj%memory_bytes()
   end function dense_memory
   !> The springs of the current modes into a condensed contact system: dk =
   !! kc - kref, added to S and factorized; a singular pivot is reported with
   !! its global equation (ceq) in bad_eq and STAT_SINGULAR naming `what`.
   !! Only the entries of a pair's contact equations (ppos > 0; 4 of the 16
   !! dofs of a node-to-node pair's arrays) are formed: the others, which no
   !! system reads, keep the zero the callers give dk at its allocation (a
   !! pass over the whole arrays cost 3 % of the 301-pair benchmark).
   subroutine set_contact_springs(dense, ppos, ceq, kc, kref, dk, what, bad_eq, status)
      type(contact_dense_t), intent(inout) :: dense
      integer, intent(in) :: ppos(:, :)             !! (nd, npair) position of each pair dof in ceq
      integer, intent(in) :: ceq(:)                 !! global equations of the contact equations
      real(dp), intent(in) :: kc(:, :, :)           !! (nd, nd, npair) spring matrices
      real(dp), intent(in) :: kref(:, :, :)         !! (nd, nd, npair) reference springs in S
      real(dp), intent(inout) :: dk(:, :, :)        !! (nd, nd, npair) kc - kref, kept
      character(len=*), intent(in) :: what          !! the system, for the message
      integer, intent(out) :: bad_eq                !! equation of a singular pivot, 0 if none
      type(status_t), intent(inout) :: status
      integer :: j, a, b
      bad_eq = 0
      do j = 1, size(ppos, 2)
         do b = 1, size(ppos, 1)
            if (ppos(b, j) <= 0) cycle
            do a = 1, size(ppos, 1)
               if (ppos(a, j) > 0) dk(a, b, j) = kc(a, b, j) - kref(a, b, j)
            end do
         end do
      end do
      call dense%set_springs(ppos, dk, status)
      if (.not. status%ok()) return
      if (dense%bad > 0) then
         bad_eq = ceq(dense%bad)
         call status%set(STAT_SINGULAR, 'zero pivot at contact equation '//itoa(bad_eq)// &
                         ' of '//what)
      end if
   end subroutine set_contact_springs
end module contact_dense
