!> The dense system of the contact equations solved in the springs' own
!! coordinates (for contact_dense).
!!
!! A pair's spring acts on the relative displacement of its nodes only: its
!! matrix K_c,j (nd x nd) has rank 2 (normal and tangent) whatever nd, and so
!! have the reference springs K_ref,j, in the same directions.  With Q_j an
!! orthonormal basis of the range of K_ref,j (eigenvectors, LAPACK dsyev) and
!! U the n_c x r matrix of all pairs' Q_j (r = sum of the ranks, about n_c/2),
!! every set of springs is K_c - K_ref = U D U^T with D block diagonal
!! (D_j = Q_j^T (K_c,j - K_ref,j) Q_j), checked pair by pair: a spring matrix
!! outside the range of its reference springs (by more than 1e-12 of their
!! scale), or stiffer than 1e4 times them (penalty springs, where the formula
!! below would lose digits), leaves the system to the direct factorization of
!! contact_dense.
!! With S fixed, Woodbury's identity in the form that needs no inverse of D
!! (D is zero for a pair whose springs equal the reference ones),
!!
!!     (S + U D U^T)^-1 g = y - V (t - z),   y = S^-1 g,  t = U^T y,
!!     V = S^-1 U F^-1,  F = U^T S^-1 U,     (F^-1 + D) z = F^-1 t,
!!
!! turns a new set of springs into a Cholesky factorization of the r x r
!! matrix F^-1 + D (r^3/3 flops against n_c^3/3, about 8 times fewer), and a
!! solve into two triangular solves with S's factor, two with that of
!! F^-1 + D and two products (S's factor, V and F^-1 are computed once).
!! F^-1 + D is singular exactly when S + K_c is (det(S + U D U^T) =
!! det S det F det(F^-1 + D)); a pivot of its Cholesky factor with
!! l_kk^2 <= 1e-12 c_kk, or a failed factorization, leaves the decision, and
!! the report of the singular equation, to the direct factorization.
!!
!! A factor kept across sets of springs.  The springs of a rough interface
!! change a little at every solution (Newton's tangents), so F^-1 + D
!! changes a little, and its factorization (r^3/3 flops, 1.8 ms at r = 602)
!! costs more than the rest of a solve.  A new set of symmetric springs
!! therefore keeps the factor of an earlier one, F^-1 + D_0, and each solve
!! of (F^-1 + D) z = F^-1 t runs the conjugate gradient method preconditioned
!! by it (two triangular solves an iteration, r^2 flops, and the blocks of
!! D - D_0: the product (F^-1 + D_0) p is carried along, as the preconditioned
!! solve itself gives it), until the residual is 1e-15 of the right-hand
!! side's: the preconditioned matrix differs from I by (F^-1 + D_0)^-1 (D -
!! D_0), so a small or low-rank change of springs converges in a few
!! iterations.  A solve that has not converged in PCG_MAX iterations, or
!! meets a non-positive curvature (the matrix is not positive definite),
!! factorizes F^-1 + D and solves with it, with the pivot test above; one
!! that needed more than PCG_REFRESH iterations has the next set of springs
!! factorized.  Either way the caller refines the solution against S + K_c
!! itself where Woodbury's formula may lose digits (contact_dense).
!!
!! A right-hand side made of the springs' own forces -- the later solutions
!! of an attempt, whose out-of-balance forces are spring forces, equal and
!! opposite on a pair's nodes -- lies in the range of U: g = U f with
!! f = U^T g when no two pair dofs share an equation (U's columns then
!! orthonormal).  Then S^-1 g = V F f, t = F f, and the solution is x = V z
!! with (F^-1 + D) z = f: neither S's factor (two triangular solves of n_c)
!! nor the product with F^-1 is needed, about half the work of a solution.
!! The test g = U f is to RANGE_RHS_ULPS rounding units of g, so the part
!! left out moves x no more than the solve's own rounding.
!!
!! Ref: W. W. Hager, "Updating the inverse of a matrix", SIAM Review 31
!!      (1989) 221-239 (the Sherman-Morrison-Woodbury formula); G. H. Golub,
!!      C. F. Van Loan, Matrix Computations, 4th ed. (2013), sec. 11.5
!!      (preconditioned conjugate gradients); LAPACK Users' Guide, 3rd ed.
!!      (1999), dsyev, dpotrf/dpotri, dtrsv, dgemm, dgemv, dsymv.
module contact_projection
   use kinds, only: dp, i8
   use lapack_interfaces, only: dsyev, dpotrf, dpotri, dpotrs, dtrsv, dgemm, dgemv, dtrsm, dsyrk
   implicit none
   private
   public :: contact_projection_t

   !> Relative size below which an eigenvalue of K_ref,j is zero.
   real(dp), parameter :: RANK_TOL = 1.0e-10_dp
   !> Largest part of a spring matrix outside the range of its reference
   !! springs, relative to their scale.
   real(dp), parameter :: RANGE_TOL = 1.0e-12_dp
   !> Relative pivot threshold of F^-1 + D (the skyline solver's).
   real(dp), parameter :: PIVOT_TOL = 1.0e-12_dp
   !> The coordinates are used when r <= MAX_SHARE n_c.
   real(dp), parameter :: MAX_SHARE = 0.6_dp
   !> Largest entry of D_j, relative to the scale of the reference springs,
   !! taken in the coordinates.  Woodbury's x = y - V (t - z) cancels: the
   !! error of the springs' relative displacements grows like eps |D|/|F^-1|,
   !! and so does that of their forces relative to the load (measured: the
   !! penalty springs of ideal contact, 1e8 times stiffer than the bodies,
   !! left the bodies out of equilibrium by 1.5e-7 of the load).  1e4 keeps
   !! it near 1e-12; stiffer springs go to the direct factorization, which is
   !! backward stable for them.
   real(dp), parameter :: MAX_STIFFNESS_RATIO = 1.0e4_dp
   !> Conjugate gradients with a kept factor: relative residual of
   !! convergence, most iterations of a solve (about the cost of a
   !! factorization at r = 602), and the iterations beyond which the next set
   !! of springs is factorized.
   real(dp), parameter :: PCG_TOL = 1.0e-15_dp
   integer, parameter :: PCG_MAX = 30
   integer, parameter :: PCG_REFRESH = 8
   !> Largest asymmetry of a D_j, relative to the scale of the reference
   !! springs, for which the factor of earlier springs is kept (conjugate
   !! gradients need a symmetric matrix).
   real(dp), parameter :: SYM_TOL = 1.0e-14_dp
   !> A right-hand side g is taken as U f, f = U^T g, when g - U f is at most
   !! this many rounding units of g's largest entry: the part left out then
   !! moves the solution no more than the rounding of the solve itself.
   real(dp), parameter :: RANGE_RHS_ULPS = 8.0_dp
   !> Pairs from which S is held in the pairs' bases (rotated_setup), as the
   !! increment predictor's and the kept factorization's limit: below, the
   !! set-up costs little either way, and the suite's small models keep their
   !! round-off (a deck of 13 pairs and a stiffness ratio of 3e5 between its
   !! bodies, robust_zero/zero_two_materials_q8, came to rest at another of
   !! its zero-load positions with the rotated form).
   integer, parameter :: ROTATE_MIN_PAIRS = 200

   type :: contact_projection_t
      logical :: ready = .false.               !! set up, and worth using
      integer :: n = 0                         !! contact equations
      integer :: r = 0                         !! spring coordinates
      integer, allocatable :: qoff(:)          !! (npair) offset of a pair's coordinates
      integer, allocatable :: qrank(:)         !! (npair) their number
      real(dp), allocatable :: q(:, :, :)      !! (nd, nd, npair) columns 1:qrank: Q_j
      real(dp), allocatable :: kscale(:)       !! (npair) largest entry of K_ref,j
      real(dp), allocatable :: ls(:, :)        !! (n, n) Cholesky factor of S (upper)
      real(dp), allocatable :: v(:, :)         !! (n, r) S^-1 U F^-1
      logical :: rotated = .false.             !! S held in the pairs' bases (below)
      integer :: rotate_min_pairs = ROTATE_MIN_PAIRS  !! pairs from which it is
      integer :: p = 0                         !! n - r: the complements' coordinates
      integer, allocatable :: qm(:)            !! (npair) a pair's valid dofs (its basis)
      integer, allocatable :: iv(:, :)         !! (nd, npair) columns 1:qm: those dofs, in
                                               !! order (valid_dofs of the set-up's ppos)
      integer, allocatable :: poff(:)          !! (npair) offset of its complement's coordinates
      real(dp), allocatable :: rp(:, :)        !! (p, p) Cholesky factor of S_PP (upper)
      real(dp), allocatable :: gm(:, :)        !! (p, r) G = S_PP^-1 S_PU
      real(dp), allocatable :: gp(:), yp(:)    !! (p) work: g_P, S_PP^-1 g_P
      real(dp), allocatable :: finv(:, :)      !! (r, r) F^-1
      real(dp), allocatable :: c(:, :)         !! (r, r) F^-1 + D, then its factor
      real(dp), allocatable :: cdiag(:)        !! (r) its diagonal
      real(dp), allocatable :: t(:), z(:)      !! (r) work
      real(dp), allocatable :: zr(:)           !! (r) right-hand side of a coordinates solve, kept
      real(dp), allocatable :: d(:, :)         !! (nd, nd) work: D_j
      real(dp), allocatable :: dcur(:, :, :)   !! (mr, mr, npair) D_j of the current springs,
                                               !! mr the largest rank (2: normal and tangent)
      real(dp), allocatable :: dfac(:, :, :)   !! (mr, mr, npair) D_j of the factor in c
      logical :: factored = .false.            !! c holds the factor of F^-1 + dfac
      logical :: stale = .false.               !! dcur differs from dfac: solves iterate
      real(dp), allocatable :: px(:), pr(:), pp(:), pq(:), pw(:)  !! (r) work of the iterations
      real(dp), allocatable :: pa(:)           !! (r) (F^-1 + dfac) pp, carried along
      integer :: last_iterations = 0           !! iterations of the last solve (0: direct)
      real(dp) :: stiffness = 0.0_dp           !! largest |D_j| / scale of K_ref,j
                                               !! of the current springs
      logical :: symmetric = .true.            !! every D_j of the current springs is symmetric
      integer :: factorizations = 0            !! factorizations of F^-1 + D so far
      integer :: iterations = 0                !! conjugate gradient iterations so far
      integer :: iterative_solves = 0          !! solves by them so far
      logical :: disjoint = .false.            !! no two pair dofs share a contact
                                               !! equation (U's blocks disjoint)
      integer :: range_solves = 0              !! solves of a right-hand side in the range of U
   contains
      procedure :: setup => projection_setup
      procedure :: set_springs => projection_set_springs
      procedure :: solve => projection_solve
      procedure :: memory_bytes => projection_memory
      procedure, private :: refactor => projection_refactor
      procedure, private :: pcg => projection_pcg
      procedure, private :: factor_solve => projection_factor_solve
      procedure, private :: coordinates_solve
      procedure, private :: in_range => projection_in_range
   end type contact_projection_t

contains

   !> The springs' coordinates of the pairs (from the reference springs) and
   !! the fixed matrices of S; `ready` stays false when they would not pay
   !! or S is not positive definite.
   subroutine projection_setup(this, s, ppos, kref)
      class(contact_projection_t), intent(inout) :: this
      real(dp), intent(in) :: s(:, :)              !! (n, n) S, symmetric
      integer, intent(in) :: ppos(:, :)            !! (nd, npair) positions of the pairs' dofs
      real(dp), intent(in) :: kref(:, :, :)        !! (nd, nd, npair) reference springs
      real(dp), allocatable :: w(:, :), f(:, :)
      integer :: j, k, a, nd, np, info, col
      this%ready = .false.
      if (allocated(this%qoff)) deallocate (this%qoff, this%qrank, this%q, this%kscale, this%d, &
                                            this%qm, this%poff, this%iv)
      if (allocated(this%ls)) deallocate (this%ls)
      if (allocated(this%v)) deallocate (this%v)
      if (allocated(this%rp)) deallocate (this%rp, this%gm, this%gp, this%yp)
      this%rotated = .false.
      if (allocated(this%finv)) deallocate (this%finv)
      if (allocated(this%c)) deallocate (this%c, this%cdiag, this%t, this%z, this%zr, this%dcur, &
                                         this%dfac, this%px, &
                                         this%pr, this%pp, this%pq, this%pw, this%pa)
      this%factored = .false.
      this%stale = .false.
      this%last_iterations = 0
      this%n = size(s, 1)
      nd = size(ppos, 1)
      np = size(ppos, 2)
      allocate (this%qoff(np), this%qrank(np), this%q(nd, nd, np), this%kscale(np), &
                this%d(nd, nd), this%qm(np), this%poff(np), this%iv(nd, np))
      call pair_bases(ppos, kref, this%q, this%qrank, this%qm, this%kscale, info)
      if (info /= 0) return
      ! the pairs' valid dofs, once (the loops of every later call run over them)
      do j = 1, np
         call valid_dofs(ppos(:, j), this%iv(:, j), a)
      end do
      this%r = 0
      this%p = 0
      do j = 1, np
         this%qoff(j) = this%r
         this%r = this%r + this%qrank(j)
         this%poff(j) = this%p
         this%p = this%p + this%qm(j) - this%qrank(j)
      end do
      if (this%r < 1 .or. real(this%r, dp) > MAX_SHARE*this%n) return
      ! U's blocks are disjoint when no contact equation belongs to two pair
      ! dofs: U then has orthonormal columns, and U^T g gives g's coordinates
      block
         integer, allocatable :: cnt(:)
         allocate (cnt(this%n))
         cnt = 0
         do j = 1, np
            do a = 1, nd
               if (ppos(a, j) > 0) cnt(ppos(a, j)) = cnt(ppos(a, j)) + 1
            end do
         end do
         this%disjoint = all(cnt <= 1)
         ! every equation one pair dof's: the pairs' bases rotate the whole of S
         this%rotated = all(cnt == 1) .and. this%r + this%p == this%n .and. &
                        np >= this%rotate_min_pairs
      end block
      if (this%rotated) then
         call rotated_setup(this, s, ppos, info)
         if (info /= 0) return
         call allocate_work(this, nd, np)
         this%range_solves = 0
         this%ready = .true.
         return
      end if
      ! (allocated before the copy: the sanitizers' build read the bounds of the unallocated
      ! component in the assignment's reallocation test, garbage, as an integer overflow)
      allocate (this%ls(this%n, this%n))
      this%ls = s
      call dpotrf('U', this%n, this%ls, this%n, info)
      if (info /= 0) return
      ! W = S^-1 U, F = U^T W
      allocate (w(this%n, this%r), f(this%r, this%r))
      w = 0.0_dp
      do j = 1, np
         do k = 1, this%qrank(j)
            do a = 1, nd
               if (ppos(a, j) > 0) w(ppos(a, j), this%qoff(j) + k) = this%q(a, k, j)
            end do
         end do
      end do
      call dpotrs('U', this%n, this%r, this%ls, this%n, w, this%n, info)
      if (info /= 0) return
      f = 0.0_dp
      do j = 1, np
         do k = 1, this%qrank(j)
            do a = 1, nd
               if (ppos(a, j) <= 0) cycle
               do col = 1, this%r
                  f(this%qoff(j) + k, col) = f(this%qoff(j) + k, col) + &
                        this%q(a, k, j)*w(ppos(a, j), col)
               end do
            end do
         end do
      end do
      f = 0.5_dp*(f + transpose(f))
      call dpotrf('U', this%r, f, this%r, info)
      if (info == 0) call dpotri('U', this%r, f, this%r, info)
      if (info /= 0) return
      do col = 1, this%r
         f(col + 1:, col) = f(col, col + 1:)
      end do
      call move_alloc(f, this%finv)
      allocate (this%v(this%n, this%r))
      call dgemm('N', 'N', this%n, this%r, this%r, 1.0_dp, w, this%n, this%finv, this%r, 0.0_dp, &
                 this%v, this%n)
      call allocate_work(this, nd, np)
      this%range_solves = 0
      this%ready = .true.
   end subroutine projection_setup

   !> The arrays of the springs' coordinates and of the iterations.
   subroutine allocate_work(this, nd, np)
      class(contact_projection_t), intent(inout) :: this
      integer, intent(in) :: nd, np
      allocate (this%c(this%r, this%r), this%cdiag(this%r), this%t(this%r), this%z(this%r), &
                this%zr(this%r), &
                this%dcur(max(1, maxval(this%qrank)), max(1, maxval(this%qrank)), np), &
                this%dfac(max(1, maxval(this%qrank)), max(1, maxval(this%qrank)), np), &
                this%px(this%r), this%pr(this%r), &
                this%pp(this%r), &
                this%pq(this%r), this%pw(this%r), this%pa(this%r))
      this%dcur = 0.0_dp
      this%dfac = 0.0_dp
      if (nd < 0) return
   end subroutine allocate_work

   !> S in the pairs' orthonormal bases (every contact equation one pair dof's):
   !! Q = [U P], P the complements of the reference springs' ranges, and
   !! Q^T S Q = [S_UU S_UP; S_PU S_PP].  Then, by the inverse of a 2 x 2 block
   !! matrix, F^-1 = (U^T S^-1 U)^-1 = S_UU - S_UP S_PP^-1 S_PU (the Schur
   !! complement of S_PP), and with G = S_PP^-1 S_PU a solve of
   !! (S + U D U^T) x = g is, in these coordinates (g_U = U^T g, g_P = P^T g),
   !!     y_P = S_PP^-1 g_P,  (F^-1 + D) x_U = g_U - G^T g_P,  x_P = y_P - G x_U.
   !! The set-up is a Cholesky factor of S_PP (p = n - r equations), two
   !! triangular solves with r columns and a symmetric rank-p update, about
   !! p^3/3 + 2 p^2 r + p r^2 flops, instead of S's factor, S^-1 U, F's inverse and V
   !! (n^3/3 + 2 n^2 r + r^3 + 2 n r^2); a solve two triangular solves of p
   !! equations and two products with G instead of n and V.
   subroutine rotated_setup(this, s, ppos, info)
      class(contact_projection_t), intent(inout) :: this
      real(dp), intent(in) :: s(:, :)
      integer, intent(in) :: ppos(:, :)
      integer, intent(out) :: info
      real(dp), allocatable :: sq(:, :), qsq(:, :)
      integer :: j, k, a, n, r, p, col, ia, iv(size(ppos, 1)), m
      n = this%n
      r = this%r
      p = this%p
      ! Q^T S Q column by column: S q for a basis vector q (its pair's valid
      ! dofs), then Q^T of it
      allocate (sq(n, 1), qsq(n, n))
      do j = 1, size(ppos, 2)
         call valid_dofs(ppos(:, j), iv, m)
         do k = 1, this%qm(j)
            col = basis_index(this, j, k)
            sq(:, 1) = 0.0_dp
            do ia = 1, m
               a = iv(ia)
               sq(:, 1) = sq(:, 1) + this%q(a, k, j)*s(:, ppos(a, j))
            end do
            call rotate_in(sq(:, 1), qsq(:, col))
         end do
      end do
      deallocate (sq)
      allocate (this%rp(max(1, p), max(1, p)), this%gm(max(1, p), r), this%gp(max(1, p)), &
                this%yp(max(1, p)))
      this%rp = 0.0_dp
      this%gm = 0.0_dp
      if (p > 0) then
         this%rp(1:p, 1:p) = qsq(r + 1:n, r + 1:n)
         call dpotrf('U', p, this%rp, p, info)
         if (info /= 0) return
         ! Z = R^-T S_PU into gm; F^-1 = S_UU - Z^T Z; G = R^-1 Z
         this%gm(1:p, :) = qsq(r + 1:n, 1:r)
         call dtrsm('L', 'U', 'T', 'N', p, r, 1.0_dp, this%rp, p, this%gm, p)
      end if
      allocate (this%finv(r, r))
      this%finv = qsq(1:r, 1:r)
      if (p > 0) then
         call dsyrk('U', 'T', r, p, -1.0_dp, this%gm, p, 1.0_dp, this%finv, r)
         call dtrsm('L', 'U', 'N', 'N', p, r, 1.0_dp, this%rp, p, this%gm, p)
      end if
      do col = 1, r
         this%finv(col + 1:, col) = this%finv(col, col + 1:)
      end do
      info = 0

   contains

      !> y = Q^T x.
      subroutine rotate_in(x, y)
         real(dp), intent(in) :: x(:)
         real(dp), intent(out) :: y(:)
         integer :: jj, kk, ib, mm, ivv(size(ppos, 1))
         real(dp) :: w
         do jj = 1, size(ppos, 2)
            call valid_dofs(ppos(:, jj), ivv, mm)
            do kk = 1, this%qm(jj)
               w = 0.0_dp
               do ib = 1, mm
                  w = w + this%q(ivv(ib), kk, jj)*x(ppos(ivv(ib), jj))
               end do
               y(basis_index(this, jj, kk)) = w
            end do
         end do
      end subroutine rotate_in
   end subroutine rotated_setup

   !> The coordinate of pair j's basis vector k: 1..r the ranges (U), r+1..n
   !! the complements (P).
   pure integer function basis_index(this, j, k) result(i)
      class(contact_projection_t), intent(in) :: this
      integer, intent(in) :: j, k
      if (k <= this%qrank(j)) then
         i = this%qoff(j) + k
      else
         i = this%r + this%poff(j) + k - this%qrank(j)
      end if
   end function basis_index

   !> The valid dofs of a pair (ppos > 0), in order.
   pure subroutine valid_dofs(pos, iv, m)
      integer, intent(in) :: pos(:)
      integer, intent(out) :: iv(:), m
      integer :: a
      m = 0
      do a = 1, size(pos)
         if (pos(a) > 0) then
            m = m + 1
            iv(m) = a
         end if
      end do
   end subroutine valid_dofs

   !> Q_j, an orthonormal basis of the range of each pair's reference springs
   !! on its valid dofs, and their scale; info /= 0 if LAPACK fails.
   subroutine pair_bases(ppos, kref, q, qrank, qm, kscale, info)
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(in) :: kref(:, :, :)
      real(dp), intent(out) :: q(:, :, :), kscale(:)
      integer, intent(out) :: qrank(:), qm(:), info
      real(dp) :: a(size(ppos, 1), size(ppos, 1)), ev(size(ppos, 1)), work(4*size(ppos, 1))
      integer :: idx(size(ppos, 1)), j, m, k, nd, l
      nd = size(ppos, 1)
      q = 0.0_dp
      qrank = 0
      qm = 0
      kscale = 0.0_dp
      info = 0
      do j = 1, size(ppos, 2)
         call valid_dofs(ppos(:, j), idx, m)
         qm(j) = m
         if (m == 0) cycle
         a(1:m, 1:m) = kref(idx(1:m), idx(1:m), j)
         kscale(j) = maxval(abs(a(1:m, 1:m)))
         if (.not. kscale(j) > 0.0_dp) then
            ! no springs: the complement is the whole of the pair's dofs
            do k = 1, m
               q(idx(k), k, j) = 1.0_dp
            end do
            cycle
         end if
         call dsyev('V', 'U', m, a, nd, ev, work, size(work), info)
         if (info /= 0) return
         do k = 1, m
            if (ev(k) > RANK_TOL*maxval(abs(ev(1:m)))) then
               qrank(j) = qrank(j) + 1
               q(idx(1:m), qrank(j), j) = a(1:m, k)
            end if
         end do
         ! columns qrank+1 .. m: the complement of the range (the rest of the
         ! orthonormal eigenvectors), for the rotated form of S
         l = qrank(j)
         do k = 1, m
            if (.not. ev(k) > RANK_TOL*maxval(abs(ev(1:m)))) then
               l = l + 1
               q(idx(1:m), l, j) = a(1:m, k)
            end if
         end do
      end do
   end subroutine pair_bases

   !> F^-1 + D for the springs kc (in the order of the pairs): factorized,
   !! or, for symmetric springs after a solve that converged in at most
   !! PCG_REFRESH iterations, left to conjugate gradients preconditioned by the
   !! factor of earlier springs.  done = .false. when a spring matrix leaves
   !! its reference springs' range or F^-1 + D is not clearly positive
   !! definite (the caller factorizes directly).
   subroutine projection_set_springs(this, ppos, kc, done)
      class(contact_projection_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(in) :: kc(:, :, :)
      logical, intent(out) :: done
      integer :: j, k, l, a, b, rk, m, ia, ib
      integer :: iv(size(ppos, 1))
      real(dp) :: recon
      logical :: symmetric
      done = .false.
      if (.not. this%ready) return
      symmetric = .true.
      this%stiffness = 0.0_dp
      do j = 1, size(ppos, 2)
         rk = this%qrank(j)
         ! the pair's valid dofs, in order (a node-to-node pair uses 4 of its slots)
         m = this%qm(j)
         iv(1:m) = this%iv(1:m, j)
         ! D_j = Q_j^T kc_j Q_j on the valid dofs
         do l = 1, rk
            do k = 1, rk
               this%d(k, l) = 0.0_dp
               do ib = 1, m
                  b = iv(ib)
                  do ia = 1, m
                     a = iv(ia)
                     this%d(k, l) = this%d(k, l) + this%q(a, k, j)*kc(a, b, j)*this%q(b, l, j)
                  end do
               end do
            end do
         end do
         if (rk > 0) then
            if (.not. maxval(abs(this%d(1:rk, 1:rk))) <= MAX_STIFFNESS_RATIO*this%kscale(j)) return
            this%stiffness = max(this%stiffness, maxval(abs(this%d(1:rk, 1:rk)))/this%kscale(j))
         end if
         ! kc_j = Q_j D_j Q_j^T, or the coordinates do not hold it
         do ib = 1, m
            b = iv(ib)
            do ia = 1, m
               a = iv(ia)
               recon = 0.0_dp
               do l = 1, rk
                  do k = 1, rk
                     recon = recon + this%q(a, k, j)*this%d(k, l)*this%q(b, l, j)
                  end do
               end do
               if (.not. abs(kc(a, b, j) - recon) <= &
                     RANGE_TOL*(this%kscale(j) + abs(kc(a, b, j)))) then
                  return
               end if
            end do
         end do
         do l = 1, rk
            do k = 1, l - 1
               if (.not. abs(this%d(k, l) - this%d(l, k)) <= SYM_TOL*this%kscale(j)) then
                  symmetric = .false.
               end if
            end do
         end do
         this%dcur(:, :, j) = 0.0_dp
         this%dcur(1:rk, 1:rk, j) = this%d(1:rk, 1:rk)
      end do
      this%symmetric = symmetric
      if (this%factored .and. symmetric .and. this%last_iterations <= PCG_REFRESH) then
         this%stale = any(abs(this%dcur - this%dfac) > 0.0_dp)
         done = .true.
         return
      end if
      call this%refactor(done)
   end subroutine projection_set_springs

   !> Factorize F^-1 + D of the current springs; ok = .false. when it is not
   !! clearly positive definite.
   subroutine projection_refactor(this, ok)
      class(contact_projection_t), intent(inout) :: this
      logical, intent(out) :: ok
      integer :: j, k, rk, o, info
      ok = .false.
      this%factored = .false.
      this%stale = .false.
      this%last_iterations = 0
      this%c = this%finv
      do j = 1, size(this%qrank)
         rk = this%qrank(j)
         o = this%qoff(j)
         this%c(o + 1:o + rk, o + 1:o + rk) = this%c(o + 1:o + rk, o + 1:o + rk) + &
               this%dcur(1:rk, 1:rk, j)
      end do
      do k = 1, this%r
         this%cdiag(k) = this%c(k, k)
      end do
      call dpotrf('U', this%r, this%c, this%r, info)
      if (info /= 0) return
      do k = 1, this%r
         if (this%c(k, k)**2 <= PIVOT_TOL*this%cdiag(k)) return
      end do
      this%dfac = this%dcur
      this%factored = .true.
      this%factorizations = this%factorizations + 1
      ok = .true.
   end subroutine projection_refactor

   !> w = (F^-1 + dfac)^-1 w with the factor in c (two triangular solves).
   subroutine projection_factor_solve(this, w)
      class(contact_projection_t), intent(in) :: this
      real(dp), intent(inout) :: w(:)
      call dtrsv('U', 'T', 'N', this%r, this%c, this%r, w, 1)
      call dtrsv('U', 'N', 'N', this%r, this%c, this%r, w, 1)
   end subroutine projection_factor_solve

   !> z = (F^-1 + dcur)^-1 z by conjugate gradients preconditioned by the
   !! factor of F^-1 + dfac; converged = .false. (z undefined) when the
   !! residual is not below PCG_TOL of the right-hand side's after PCG_MAX
   !! iterations or the curvature is not positive.
   subroutine projection_pcg(this, z, converged)
      class(contact_projection_t), intent(inout) :: this
      real(dp), intent(inout) :: z(:)            !! (r) right-hand side, then the solution
      logical, intent(out) :: converged
      integer :: it, j, k, l, rk, o
      real(dp) :: bnorm, rho, rho_new, pap, alpha
      converged = .false.
      this%iterative_solves = this%iterative_solves + 1
      this%last_iterations = 0
      bnorm = norm2(z)
      if (.not. bnorm > 0.0_dp) then
         converged = bnorm <= 0.0_dp          ! zero (NaN: not)
         return
      end if
      this%px = 0.0_dp
      this%pr = z
      this%pw = this%pr
      call this%factor_solve(this%pw)
      this%pp = this%pw
      this%pa = this%pr
      rho = dot_product(this%pr, this%pw)
      do it = 1, PCG_MAX
         ! q = (F^-1 + D) p = (F^-1 + D_0) p + (D - D_0) p, the first term
         ! carried along (pa), the second block by block
         this%pq = this%pa
         do j = 1, size(this%qrank)
            rk = this%qrank(j)
            o = this%qoff(j)
            do l = 1, rk
               do k = 1, rk
                  this%pq(o + k) = this%pq(o + k) + &
                                   (this%dcur(k, l, j) - this%dfac(k, l, j))*this%pp(o + l)
               end do
            end do
         end do
         pap = dot_product(this%pp, this%pq)
         this%last_iterations = it
         this%iterations = this%iterations + 1
         if (.not. pap > 0.0_dp) return
         alpha = rho/pap
         this%px = this%px + alpha*this%pp
         this%pr = this%pr - alpha*this%pq
         if (norm2(this%pr) <= PCG_TOL*bnorm) then
            z = this%px
            converged = .true.
            return
         end if
         this%pw = this%pr
         call this%factor_solve(this%pw)
         rho_new = dot_product(this%pr, this%pw)
         this%pp = this%pw + (rho_new/rho)*this%pp
         this%pa = this%pr + (rho_new/rho)*this%pa
         rho = rho_new
      end do
   end subroutine projection_pcg

   !> x = (S + K_c)^-1 x for the springs of the last set_springs; ok =
   !! .false. when they turned out not to be clearly positive definite in the
   !! coordinates (the caller factorizes directly).
   subroutine projection_solve(this, ppos, x, ok)
      class(contact_projection_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(inout) :: x(:)            !! (n), contiguous
      logical, intent(out) :: ok
      integer :: j, k, a
      ok = .true.
      if (this%rotated) then
         call rotated_solve(this, ppos, x, ok)
         return
      end if
      if (this%in_range(ppos, x)) then
         ! g = U f (the springs' own forces: the later solutions of an
         ! attempt): x = V (F^-1 + D)^-1 f, without S's factor or F^-1, since
         ! then y = S^-1 U f = V F f = V t and t = F f, F^-1 t = f
         this%z = this%t
         call this%coordinates_solve(ok)
         if (.not. ok) return
         call dgemv('N', this%n, this%r, 1.0_dp, this%v, this%n, this%z, 1, 0.0_dp, x, 1)
         this%range_solves = this%range_solves + 1
         return
      end if
      call dtrsv('U', 'T', 'N', this%n, this%ls, this%n, x, 1)
      call dtrsv('U', 'N', 'N', this%n, this%ls, this%n, x, 1)
      ! t = U^T y
      do j = 1, size(ppos, 2)
         do k = 1, this%qrank(j)
            this%t(this%qoff(j) + k) = 0.0_dp
            do a = 1, size(ppos, 1)
               if (ppos(a, j) > 0) then
                  this%t(this%qoff(j) + k) = this%t(this%qoff(j) + k) + &
                        this%q(a, k, j)*x(ppos(a, j))
               end if
            end do
         end do
      end do
      ! z = (F^-1 + D)^-1 F^-1 t;  x = y - V (t - z)
      call dgemv('N', this%r, this%r, 1.0_dp, this%finv, this%r, this%t, 1, 0.0_dp, this%z, 1)
      call this%coordinates_solve(ok)
      if (.not. ok) return
      this%t = this%t - this%z
      call dgemv('N', this%n, this%r, -1.0_dp, this%v, this%n, this%t, 1, 1.0_dp, x, 1)
   end subroutine projection_solve

   !> projection_solve with S in the pairs' bases (rotated_setup): a right-hand
   !! side of the springs' own forces (g = U f) has g_P = 0.
   subroutine rotated_solve(this, ppos, x, ok)
      class(contact_projection_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(inout) :: x(:)
      logical, intent(out) :: ok
      integer :: j, k, a, ia, m, iv(size(ppos, 1)), p, r
      real(dp) :: w
      logical :: range
      p = this%p
      r = this%r
      range = this%in_range(ppos, x)
      if (range) then
         this%z = this%t
      else
         ! g_U (t) and g_P
         do j = 1, size(ppos, 2)
            m = this%qm(j)
            iv(1:m) = this%iv(1:m, j)
            do k = 1, this%qm(j)
               w = 0.0_dp
               do ia = 1, m
                  a = iv(ia)
                  w = w + this%q(a, k, j)*x(ppos(a, j))
               end do
               if (k <= this%qrank(j)) then
                  this%t(this%qoff(j) + k) = w
               else
                  this%gp(this%poff(j) + k - this%qrank(j)) = w
               end if
            end do
         end do
         ! y_P = S_PP^-1 g_P;  right-hand side g_U - G^T g_P
         this%z = this%t
         if (p > 0) then
            this%yp(1:p) = this%gp(1:p)
            call dtrsv('U', 'T', 'N', p, this%rp, p, this%yp, 1)
            call dtrsv('U', 'N', 'N', p, this%rp, p, this%yp, 1)
            call dgemv('T', p, r, -1.0_dp, this%gm, p, this%gp, 1, 1.0_dp, this%z, 1)
         end if
      end if
      call this%coordinates_solve(ok)
      if (.not. ok) return
      ! x_P = y_P - G x_U (y_P = 0 for g = U f)
      if (p > 0) then
         if (range) this%yp(1:p) = 0.0_dp
         call dgemv('N', p, r, -1.0_dp, this%gm, p, this%z, 1, 1.0_dp, this%yp, 1)
      end if
      ! x = Q [x_U; x_P]
      do j = 1, size(ppos, 2)
         m = this%qm(j)
         iv(1:m) = this%iv(1:m, j)
         do ia = 1, m
            a = iv(ia)
            w = 0.0_dp
            do k = 1, this%qm(j)
               if (k <= this%qrank(j)) then
                  w = w + this%q(a, k, j)*this%z(this%qoff(j) + k)
               else
                  w = w + this%q(a, k, j)*this%yp(this%poff(j) + k - this%qrank(j))
               end if
            end do
            x(ppos(a, j)) = w
         end do
      end do
      if (range) this%range_solves = this%range_solves + 1
   end subroutine rotated_solve

   !> z = (F^-1 + D)^-1 z for the current springs: the kept factor's
   !! iteration, or the factor (ok = .false.: the springs are not clearly
   !! positive definite in their coordinates).  The right-hand side is kept
   !! in zr for a refactorization (pcg leaves z undefined then).
   subroutine coordinates_solve(this, ok)
      class(contact_projection_t), intent(inout) :: this
      logical, intent(out) :: ok
      logical :: converged
      ok = .true.
      if (this%stale) then
         this%zr = this%z
         call this%pcg(this%z, converged)
         if (.not. converged) then
            call this%refactor(ok)
            if (.not. ok) return
            this%z = this%zr
            call this%factor_solve(this%z)
         end if
      else
         this%last_iterations = 0
         call this%factor_solve(this%z)
      end if
   end subroutine coordinates_solve

   !> Is g = U f to RANGE_RHS_ULPS rounding units of its largest entry, with
   !! f = U^T g (into t)?  Only when U's blocks are disjoint.
   logical function projection_in_range(this, ppos, g) result(yes)
      class(contact_projection_t), intent(inout) :: this
      integer, intent(in) :: ppos(:, :)
      real(dp), intent(in) :: g(:)
      real(dp) :: gmax, w
      integer :: j, k, a, ia
      yes = .false.
      if (.not. this%disjoint) return
      gmax = maxval(abs(g))
      if (.not. gmax > 0.0_dp) return
      ! the pairs' valid dofs in order (this%iv): the sums of the loops over all
      ! of ppos that skip the others, term for term
      do j = 1, size(ppos, 2)
         do k = 1, this%qrank(j)
            w = 0.0_dp
            do ia = 1, this%qm(j)
               a = this%iv(ia, j)
               w = w + this%q(a, k, j)*g(ppos(a, j))
            end do
            this%t(this%qoff(j) + k) = w
         end do
      end do
      do j = 1, size(ppos, 2)
         do ia = 1, this%qm(j)
            a = this%iv(ia, j)
            w = 0.0_dp
            do k = 1, this%qrank(j)
               w = w + this%q(a, k, j)*this%t(this%qoff(j) + k)
            end do
            if (.not. abs(g(ppos(a, j)) - w) <= RANGE_RHS_ULPS*epsilon(1.0_dp)*gmax) return
         end do
      end do
      yes = .true.
   end function projection_in_range

   !> S's factor, V, F^-1, F^-1 + D, the bases, the springs' blocks and the
   !! iterations' vectors [bytes].
   pure integer(i8) function projection_memory(this) result(bytes)
      class(contact_projection_t), intent(in) :: this
      bytes = 0
      if (allocated(this%ls)) bytes = bytes + 8_i8*size(this%ls, kind=i8)
      if (allocated(this%v)) bytes = bytes + 8_i8*size(this%v, kind=i8)
      if (allocated(this%rp)) bytes = bytes + 8_i8*(size(this%rp, kind=i8) + size(this%gm, kind=i8))
      if (allocated(this%finv)) bytes = bytes + 8_i8*size(this%finv, kind=i8)
      if (allocated(this%c)) bytes = bytes + 8_i8*size(this%c, kind=i8)
      if (allocated(this%q)) bytes = bytes + 8_i8*size(this%q, kind=i8)
      if (allocated(this%dcur)) bytes = bytes + 16_i8*size(this%dcur, kind=i8) + 48_i8*this%r
   end function projection_memory
end module contact_projection
