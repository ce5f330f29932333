!> The bodies condensed onto the contact equations (the fast path of
!! DESIGN.md: "condense the bodies onto the contact DOFs once so that an
!! increment costs a small dense LAPACK solve").
!!
!! B = K_AB + K_ref is factorized once: K_ref gives every pair a spring of the
!! bodies' own stiffness scale in both directions, so that B is regular even
!! where the springs are the only support of a body.  The flexibility of the
!! n_c contact equations c
!!
!!     G = E_c^T B^-1 E_c        (n_c x n_c, n_c solves with unit vectors)
!!
!! turns every solve of [K_AB + K_c] dv = b, i.e. (B + dK) dv = b with
!! dK = K_c - K_ref acting on c alone, into
!!
!!     w = B^-1 b,  (I + G dK_cc) dv_c = w_c,  dv = w - B^-1 E_c dK_cc dv_c,
!!
!! a dense system of order n_c (LAPACK dgetrf/dgetrs) plus solves with the
!! existing factorization.  The first solve of an attempt computes w = B^-1 b
!! in full; the later ones have b on c only, so that w_c = G b_c needs no
!! solve at all, and `solve` returns dv at the contact equations only.  The
!! full-length increment of the attempt, the sum of its solutions,
!!
!!     sum dv = w_1 + B^-1 E_c (sum_{i>1} b_c,i - sum_i dK_cc,i dv_c,i),
!!
!! takes one more solve, in `recover`.  Ref: the static condensation of
!! substructures (e.g. Bathe, Finite Element Procedures, sec. 8.2.4).
module condensed_system
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SOLVER, STAT_SINGULAR
   use strings, only: itoa
   use contact_system, only: contact_system_t, contact_equations
   implicit none
   private
   public :: condensed_system_t

   type, extends(contact_system_t) :: condensed_system_t
      integer :: nc = 0                      !! contact equations
      integer, allocatable :: ceq(:)         !! their global equation numbers
      integer, allocatable :: pos(:)         !! (neq) position of an equation in ceq, 0 if none
      integer, allocatable :: cdof(:, :)     !! (2, ndof) (dof, node) of the nodal dofs on contact equations
      real(dp), allocatable :: kref(:, :, :) !! (nd, nd, npair) reference springs K_ref
      real(dp), allocatable :: g(:, :)       !! flexibility G (n_c x n_c)
      real(dp), allocatable :: kcc(:, :)     !! dK = K_c - K_ref assembled on c
      ! the attempt under way
      logical :: first = .true.              !! the next solve is the attempt's first
      real(dp), allocatable :: w1(:)         !! (neq) B^-1 b of the first solve
      real(dp), allocatable :: rsum(:)       !! (n_c) sum of the later right-hand sides on c
      real(dp), allocatable :: zc(:)         !! (n_c) sum of dK_cc dv_c
      real(dp), allocatable :: work(:)       !! (neq)
   contains
      procedure :: prepare => condensed_prepare
      procedure :: set_springs => condensed_set_springs
      procedure :: begin_attempt => condensed_begin_attempt
      procedure :: solve => condensed_solve
      procedure :: recover => condensed_recover
      procedure :: describe => condensed_describe
      procedure :: memory_bytes => condensed_memory
   end type condensed_system_t

contains

   !> Factorize B = K_AB + K_ref once and form the flexibility G of the
   !! contact equations from n_c solves.
   subroutine condensed_prepare(this, kref, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: kref(:, :, :)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: e(:)
      integer :: j, k, ip, idof, n
      this%condensed = .true.
      this%kref = kref
      call this%solver%restore_base()
      do j = 1, size(this%peq, 2)
         call this%solver%add_element(this%peq(:, j), kref(:, :, j))
      end do
      call this%solver%factorize(status)
      if (.not. status%ok()) then
         status%message = 'condensation: the bodies with reference springs are singular ('//status%message// &
                          '); check the restraints'
         return
      end if
      this%ceq = contact_equations(this%peq, this%neq)
      this%nc = size(this%ceq)
      allocate (this%pos(this%neq))
      this%pos = 0
      do k = 1, this%nc
         this%pos(this%ceq(k)) = k
      end do
      ! the nodal dofs whose equation is a contact equation (where solve answers)
      n = count(this%id > 0 .and. this%id <= this%neq)
      allocate (this%cdof(2, n))
      n = 0
      do ip = 1, size(this%id, 2)
         do idof = 1, 2
            if (this%id(idof, ip) <= 0) cycle
            if (this%pos(this%id(idof, ip)) == 0) cycle
            n = n + 1
            this%cdof(:, n) = [idof, ip]
         end do
      end do
      this%cdof = this%cdof(:, 1:n)
      allocate (this%g(this%nc, this%nc), this%kcc(this%nc, this%nc), e(this%neq))
      do j = 1, this%nc
         e = 0.0_dp
         e(this%ceq(j)) = 1.0_dp
         call this%solver%solve(e, status)
         if (.not. status%ok()) return
         this%g(:, j) = e(this%ceq)
      end do
      ! symmetric in exact arithmetic: remove the round-off asymmetry
      this%g = 0.5_dp*(this%g + transpose(this%g))
      allocate (this%w1(this%neq), this%work(this%neq), this%rsum(this%nc), this%zc(this%nc))
   end subroutine condensed_prepare

   !> dK = K_c - K_ref on the contact equations (every pair's positive
   !! equations are contact equations).
   subroutine condensed_set_springs(this, kc, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      integer :: j
      this%kcc = 0.0_dp
      do j = 1, size(this%peq, 2)
         call add_spring(this, this%peq(:, j), kc(:, :, j) - this%kref(:, :, j))
      end do
      associate (unused => status)
      end associate
   end subroutine condensed_set_springs

   !> Add a spring matrix with global equations ieq (<= 0 skipped).
   subroutine add_spring(this, ieq, ke)
      class(condensed_system_t), intent(inout) :: this
      integer, intent(in) :: ieq(:)
      real(dp), intent(in) :: ke(:, :)
      integer :: a, b, pa, pb
      do b = 1, size(ieq)
         if (ieq(b) <= 0) cycle
         pb = this%pos(ieq(b))
         do a = 1, size(ieq)
            if (ieq(a) <= 0) cycle
            pa = this%pos(ieq(a))
            this%kcc(pa, pb) = this%kcc(pa, pb) + ke(a, b)
         end do
      end do
   end subroutine add_spring

   !> A new attempt: the deferred correction starts from zero.
   subroutine condensed_begin_attempt(this)
      class(condensed_system_t), intent(inout) :: this
      this%first = .true.
      this%zc = 0.0_dp
      this%rsum = 0.0_dp
   end subroutine condensed_begin_attempt

   !> (B + dK) dv = b: dv at the dofs of the contact equations.
   subroutine condensed_solve(this, b, du, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)
      real(dp), intent(inout) :: du(:, :)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: wc(:), dvc(:)
      integer :: k
      this%bad_eq = 0
      allocate (wc(this%nc), dvc(this%nc))
      if (this%first) then
         this%w1 = b
         call this%solver%solve(this%w1, status)
         if (.not. status%ok()) return
         wc = this%w1(this%ceq)
         this%first = .false.
      else
         ! b is zero off the contact equations: w_c = G b_c
         wc = matmul(this%g, b(this%ceq))
         this%rsum = this%rsum + b(this%ceq)
      end if
      call solve_c(this, wc, dvc, status)
      if (.not. status%ok()) return
      this%zc = this%zc + matmul(this%kcc, dvc)
      do k = 1, size(this%cdof, 2)
         du(this%cdof(1, k), this%cdof(2, k)) = dvc(this%pos(this%id(this%cdof(1, k), this%cdof(2, k))))
      end do
   end subroutine condensed_solve

   !> The attempt's increment at every free dof: w_1 + B^-1 E_c (rsum - zc).
   subroutine condensed_recover(this, du, need_full, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(inout) :: du(:, :)
      logical, intent(in) :: need_full
      type(status_t), intent(inout) :: status
      integer :: ip, idof
      associate (unused => need_full)   ! the correction is one solve: always done
      end associate
      this%work = 0.0_dp
      this%work(this%ceq) = this%rsum - this%zc
      call this%solver%solve(this%work, status)
      if (.not. status%ok()) return
      this%work = this%w1 + this%work
      do ip = 1, size(this%id, 2)
         do idof = 1, 2
            if (this%id(idof, ip) > 0) du(idof, ip) = this%work(this%id(idof, ip))
         end do
      end do
   end subroutine condensed_recover

   !> Solve (I + G dK_cc) x = wc for the contact part of a solution (LAPACK
   !! dgetrf/dgetrs).  A pivot below 1e-12 of its column's largest original
   !! entry means a singular system (e.g. a body whose springs all opened),
   !! reported like the skyline solver's zero pivots, with its equation in
   !! bad_eq.
   subroutine solve_c(this, wc, x, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: wc(:)
      real(dp), intent(out) :: x(:)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: a(:, :), b(:, :), colmax(:)
      integer, allocatable :: ipiv(:)
      integer :: info, k
      interface
         subroutine dgetrf(m, n, a, lda, ipiv, info)
            import :: dp
            integer, intent(in) :: m, n, lda
            real(dp), intent(inout) :: a(lda, *)
            integer, intent(out) :: ipiv(*), info
         end subroutine dgetrf
         subroutine dgetrs(trans, n, nrhs, a, lda, ipiv, b, ldb, info)
            import :: dp
            character(len=1), intent(in) :: trans
            integer, intent(in) :: n, nrhs, lda, ldb
            real(dp), intent(in) :: a(lda, *)
            integer, intent(in) :: ipiv(*)
            real(dp), intent(inout) :: b(ldb, *)
            integer, intent(out) :: info
         end subroutine dgetrs
      end interface
      x = 0.0_dp
      if (this%nc == 0) return
      a = matmul(this%g, this%kcc)
      do k = 1, this%nc
         a(k, k) = a(k, k) + 1.0_dp
      end do
      colmax = maxval(abs(a), dim=1)
      allocate (b(this%nc, 1), ipiv(this%nc))
      call dgetrf(this%nc, this%nc, a, this%nc, ipiv, info)
      if (info < 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrf: illegal argument '//itoa(-info))
         return
      end if
      do k = 1, this%nc
         if (abs(a(k, k)) <= 1.0e-12_dp*colmax(k)) then
            this%bad_eq = this%ceq(k)
            call status%set(STAT_SINGULAR, 'zero pivot at contact equation '//itoa(this%ceq(k))// &
                            ' of the condensed contact system')
            return
         end if
      end do
      b(:, 1) = wc
      call dgetrs('N', this%nc, 1, a, this%nc, ipiv, b, this%nc, info)
      if (info /= 0) then
         call status%set(STAT_SOLVER, 'LAPACK dgetrs: illegal argument '//itoa(-info))
         return
      end if
      x = b(:, 1)
   end subroutine solve_c

   function condensed_describe(this) result(s)
      class(condensed_system_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = 'Condensed    : bodies condensed onto '//itoa(this%nc)// &
          ' contact equations (one factorization of the bodies)'
   end function condensed_describe

   !> G, dK_cc and the dense matrix of a solve, and the vectors of an attempt.
   pure function condensed_memory(this) result(bytes)
      class(condensed_system_t), intent(in) :: this
      integer(i8) :: bytes
      bytes = (3_i8*int(this%nc, i8)**2 + 2_i8*int(this%neq, i8) + 2_i8*int(this%nc, i8))*8_i8
      if (allocated(this%kref)) bytes = bytes + storage_size(this%kref, i8)/8*size(this%kref, kind=i8)
   end function condensed_memory
end module condensed_system
