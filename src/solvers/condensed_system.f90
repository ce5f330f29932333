!> The bodies condensed onto the contact equations (the fast path of
!! DESIGN.md: "condense the bodies onto the contact DOFs once so that an
!! increment costs a small dense LAPACK solve"), on any linear solver.
!!
!! B = K_AB + K_ref is factorized once: K_ref gives every pair a spring of the
!! bodies' own stiffness scale in both directions, so that B is regular even
!! where the springs are the only support of a body.  The flexibility of the
!! n_c contact equations c
!!
!!     G = E_c^T B^-1 E_c        (n_c x n_c, n_c solves with unit vectors)
!!
!! is inverted once into the condensed stiffness S_B = G^-1 (the Schur
!! complement of B onto c; Cholesky, dpotrf/dpotri).  Every solve of
!! [K_AB + K_c] dv = b, i.e. (B + dK) dv = b with dK = K_c - K_ref acting on c
!! alone, is then
!!
!!     w = B^-1 b,  (S_B + dK_cc) dv_c = S_B w_c,  dv = w - B^-1 E_c dK_cc dv_c,
!!
!! a dense symmetric system of order n_c (contact_dense: Cholesky, factorized
!! once per set of springs, the springs added entry by entry) plus solves with
!! the existing factorization.  The first solve of an attempt computes
!! w = B^-1 b in full; the later ones have b on c only, so that S_B w_c = b_c
!! needs neither a solve nor a product, and `solve` returns dv at the contact
!! equations only.  The full-length increment of the attempt, the sum of its
!! solutions,
!!
!!     sum dv = w_1 + B^-1 E_c (sum_{i>1} b_c,i - sum_i dK_cc,i dv_c,i),
!!
!! takes one more solve, in `recover`; dK_cc dv_c is summed pair by pair (at
!! most 2 nn entries a column).  (I + G dK_cc) dv_c = w_c, the system of the
!! first version, is the same system multiplied by G: the results agree to
!! round-off.  Ref: the static condensation of substructures (e.g. Bathe,
!! Finite Element Procedures, sec. 8.2.4).
module condensed_system
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SINGULAR
   use strings, only: itoa
   use contact_system, only: contact_system_t, index_contact_equations
   use contact_dense, only: contact_dense_t, set_contact_springs
   use lapack_interfaces, only: dpotrf, dpotri
   implicit none
   private
   public :: condensed_system_t

   type, extends(contact_system_t) :: condensed_system_t
      integer :: nc = 0                      !! contact equations
      integer, allocatable :: ceq(:)         !! their global equation numbers
      integer, allocatable :: pos(:)         !! (neq) position of an equation in ceq, 0 if none
      integer, allocatable :: ppos(:, :)     !! (nd, npair) position of each
                                             !! pair dof in ceq, 0 if none
      integer, allocatable :: cdof(:, :)     !! (3, ndof) (dof, node, position) of
                                             !! the nodal dofs on contact equations
      real(dp), allocatable :: kref(:, :, :) !! (nd, nd, npair) reference springs K_ref
      real(dp), allocatable :: dk(:, :, :)   !! (nd, nd, npair) dK = K_c -
                                             !! K_ref of the current springs
      type(contact_dense_t) :: dense         !! S_B = G^-1, and S_B + dK factorized
      ! the attempt under way
      logical :: first = .true.              !! the next solve is the attempt's first
      real(dp), allocatable :: w1(:)         !! (neq) B^-1 b of the first solve
      real(dp), allocatable :: rsum(:)       !! (n_c) sum of the later right-hand sides on c
      real(dp), allocatable :: zc(:)         !! (n_c) sum of dK_cc dv_c
      real(dp), allocatable :: bc_last(:)    !! (n_c) the last later right-hand side on c
      real(dp), allocatable :: zc_last(:)    !! (n_c) its dK_cc dv_c (scale_last)
      real(dp), allocatable :: xc(:)         !! (n_c) the contact part of a solution
      real(dp), allocatable :: work(:)       !! (neq)
   contains
      procedure :: prepare => condensed_prepare
      procedure :: set_springs => condensed_set_springs
      procedure :: begin_attempt => condensed_begin_attempt
      procedure :: solve => condensed_solve
      procedure :: recover => condensed_recover
      procedure :: describe => condensed_describe
      procedure :: memory_bytes => condensed_memory
      procedure :: scales_last => condensed_scales_last
      procedure :: scale_last => condensed_scale_last
   end type condensed_system_t

contains

   !> Factorize B = K_AB + K_ref once, form the flexibility G of the contact
   !! equations from n_c solves and invert it into S_B.
   subroutine condensed_prepare(this, kref, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: kref(:, :, :)
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: e(:)
      integer :: j, info
      this%condensed = .true.
      ! allocated explicitly: gfortran 12's reallocation on assignment reads the
      ! bounds of the unallocated component (UBSan: an integer overflow)
      if (allocated(this%kref)) deallocate (this%kref)
      allocate (this%kref, source=kref)
      call this%solver%restore_base()
      do j = 1, size(this%peq, 2)
         call this%solver%add_element(this%peq(:, j), kref(:, :, j))
      end do
      call this%solver%factorize(status)
      if (.not. status%ok()) then
         status%message = 'condensation: the bodies with reference springs are singular ('// &
               status%message// &
                          '); check the restraints'
         return
      end if
      ! where the contact equations sit (solve answers at the nodal dofs of cdof)
      call index_contact_equations(this%peq, this%neq, this%id, this%ceq, this%pos, this%ppos, &
                                   this%cdof)
      this%nc = size(this%ceq)
      call this%dense%init(this%nc, size(this%peq, 1), size(this%peq, 2))
      allocate (e(this%neq))
      do j = 1, this%nc
         e = 0.0_dp
         e(this%ceq(j)) = 1.0_dp
         call this%solver%solve(e, status)
         if (.not. status%ok()) return
         this%dense%s(:, j) = e(this%ceq)
      end do
      ! G is symmetric positive definite (B is): S_B = G^-1 by Cholesky
      if (this%nc > 0) then
         call dpotrf('U', this%nc, this%dense%s, this%nc, info)
         if (info == 0) call dpotri('U', this%nc, this%dense%s, this%nc, info)
         if (info /= 0) then
            call status%set(STAT_SINGULAR, &
                            'condensation: the flexibility of the contact equations is not '// &
                            'positive definite (LAPACK info '//itoa(info)// &
                            '); check the restraints')
            return
         end if
         do j = 1, this%nc
            this%dense%s(j + 1:, j) = this%dense%s(j, j + 1:)
         end do
      end if
      call this%dense%prepare_projection(this%ppos, kref)
      allocate (this%dk, mold=kref)
      this%dk = 0.0_dp
      allocate (this%w1(this%neq), this%work(this%neq), this%rsum(this%nc), this%zc(this%nc), &
                this%xc(this%nc))
   end subroutine condensed_prepare

   !> S_B + dK, dK = K_c - K_ref on the contact equations (every pair's
   !! positive equations are contact equations), factorized; a singular
   !! system is reported here, with its contact equation.
   subroutine condensed_set_springs(this, kc, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      call set_contact_springs(this%dense, this%ppos, this%ceq, kc, this%kref, this%dk, &
                               'the condensed contact system', &
                               this%bad_eq, status)
   end subroutine condensed_set_springs

   !> A new attempt: the deferred correction starts from zero.
   subroutine condensed_begin_attempt(this)
      class(condensed_system_t), intent(inout) :: this
      this%first = .true.
      this%zc = 0.0_dp
      this%rsum = 0.0_dp
      ! (allocated by the attempt's later solves only: scale_last)
      if (allocated(this%bc_last)) deallocate (this%bc_last, this%zc_last)
   end subroutine condensed_begin_attempt

   !> (B + dK) dv = b: dv at the dofs of the contact equations.
   subroutine condensed_solve(this, b, du, status)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)
      real(dp), intent(inout) :: du(:, :)
      type(status_t), intent(inout) :: status
      integer :: k, j, a, c
      if (this%first) then
         this%w1 = b
         call this%solver%solve(this%w1, status)
         if (.not. status%ok()) return
         ! S_B w_c: the dense product, once per attempt
         this%xc = matmul(this%dense%s, this%w1(this%ceq))
         this%first = .false.
      else
         ! b is zero off the contact equations: S_B w_c = S_B G b_c = b_c
         this%xc = b(this%ceq)
         this%rsum = this%rsum + this%xc
         this%bc_last = this%xc
         this%zc_last = this%zc
      end if
      call this%dense%solve(this%xc, status)
      if (.not. status%ok()) return
      if (this%dense%bad > 0) then
         this%bad_eq = this%ceq(this%dense%bad)
         call status%set(STAT_SINGULAR, 'zero pivot at contact equation '//itoa(this%bad_eq)// &
                         ' of the condensed contact system')
         return
      end if
      ! zc += dK_cc dv_c, pair by pair
      do j = 1, size(this%ppos, 2)
         do c = 1, size(this%ppos, 1)
            if (this%ppos(c, j) <= 0) cycle
            do a = 1, size(this%ppos, 1)
               if (this%ppos(a, j) <= 0) cycle
               this%zc(this%ppos(a, j)) = this%zc(this%ppos(a, j)) + &
                     this%dk(a, c, j)*this%xc(this%ppos(c, j))
            end do
         end do
      end do
      do k = 1, size(this%cdof, 2)
         du(this%cdof(1, k), this%cdof(2, k)) = this%xc(this%cdof(3, k))
      end do
      if (allocated(this%zc_last)) this%zc_last = this%zc - this%zc_last
   end subroutine condensed_solve

   pure logical function condensed_scales_last(this)
      class(condensed_system_t), intent(in) :: this
      associate (unused => this)
      end associate
      condensed_scales_last = .true.
   end function condensed_scales_last

   !> The last (later) solve as alpha times itself: its right-hand side in rsum
   !! and its dK_cc dv_c in zc (the recovery is linear in both).
   subroutine condensed_scale_last(this, alpha)
      class(condensed_system_t), intent(inout) :: this
      real(dp), intent(in) :: alpha
      if (.not. allocated(this%bc_last)) return
      this%rsum = this%rsum - (1.0_dp - alpha)*this%bc_last
      this%zc = this%zc - (1.0_dp - alpha)*this%zc_last
      this%bc_last = alpha*this%bc_last
      this%zc_last = alpha*this%zc_last
   end subroutine condensed_scale_last

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

   function condensed_describe(this) result(s)
      class(condensed_system_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = 'Condensed    : bodies condensed onto '//itoa(this%nc)// &
          ' contact equations (one factorization of the bodies)'
   end function condensed_describe

   !> S_B and the factors of the contact equations, the springs, and the
   !! vectors of an attempt.
   pure function condensed_memory(this) result(bytes)
      class(condensed_system_t), intent(in) :: this
      integer(i8) :: bytes
      bytes = this%dense%memory_bytes() + (2_i8*int(this%neq, i8) + 3_i8*int(this%nc, i8))*8_i8
      if (allocated(this%kref)) then
         bytes = bytes + 2_i8*storage_size(this%kref, i8)/8*size(this%kref, kind=i8)
      end if
   end function condensed_memory
end module condensed_system
