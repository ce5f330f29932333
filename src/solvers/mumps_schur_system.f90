!> The contact system from one sparse factorization: MUMPS eliminates every
!! equation but the n_c contact equations c and returns their dense Schur
!! complement
!!
!!     S = K_cc - K_cb K_bb^-1 K_bc          (K = K_AB, b = the other equations)
!!
!! from the factorization itself (mumps_solver%factorize_schur), so that the
!! bodies are condensed onto the contact equations for the cost of about one
!! factorization, not of n_c solves.  The springs act on c alone, so every
!! solve of [K_AB + K_c] dv = b is
!!
!!     g = b_c - K_cb K_bb^-1 b_b            (condensation, MUMPS ICNTL(26) = 1)
!!     (S + K_c) dv_c = g                    (contact_dense: Cholesky per set of springs)
!!     dv_b = K_bb^-1 (b_b - K_bc dv_c)      (expansion, MUMPS ICNTL(26) = 2)
!!
!! Only K_bb is factorized: it is regular whenever the model is regular with
!! reference springs, because its equations are those of the bodies with
!! every contact dof held.  The reference springs of the other systems
!! (K_ref, on the contact equations alone) are added to K_AB all the same,
!! so that every diagonal is positive for MUMPS's scaling and singularity
!! test (a rigid body's reference node has stiffness from springs only):
!! MUMPS returns S_ref = S + K_ref, and the springs go in as K_c - K_ref,
!! exactly as in the condensation by solves.  The first solve of
!! an attempt condenses its right-hand side; the later ones have b on c only
!! (out-of-balance spring forces), where g = b_c: they cost two dense
!! triangular solves.  The increment of the attempt away from c is, since
!! only the first right-hand side has a part on b,
!!
!!     sum dv_b = K_bb^-1 (b_1,b - K_bc sum dv_c),
!!
!! one expansion of the condensation kept by MUMPS from the first solve:
!! `recover` costs one reduced back-substitution.  With need_full = .false.
!! even that is postponed: the first right-hand sides and the contact
!! solutions of the postponed steps are summed (the equations are linear) and
!! the next recover with need_full = .true. condenses their sum and expands
!! it once, giving the dofs away from c the postponed increments too; the
!! contact dofs are exact after every solve in any case.
!!
!! The condensation is linear, g = b_c + h(b_b), and away from c the first
!! right-hand sides of a proportional load differ by a factor only (the
!! load increment; the out-of-balance force carried from the last increment
!! is a spring force, on c).  So the last b_b condensed by MUMPS is kept
!! with its h(b_b) = g - b_c: a first right-hand side whose b_b is alpha
!! times it (to 8 eps of its largest entry) gets g = b_c + alpha h(b_b)
!! without a solve -- a forward elimination through the whole factor saved
!! per increment (at 1e6 dofs 0.2 s of CPU).  MUMPS then holds no
!! condensation of the attempt, and `recover` condenses b_1 itself before
!! the expansion, as it does for postponed steps.
!!
!! Ref: MUMPS 5.5 Users' guide, sec. 5.15 (Schur complement, reduced
!!      right-hand side, ICNTL(19), ICNTL(26)); static condensation of
!!      substructures, e.g. Bathe, Finite Element Procedures, sec. 8.2.4.
module mumps_schur_system
   use kinds, only: dp, i8
   use errors, only: status_t, STAT_SOLVER, STAT_SINGULAR
   use strings, only: itoa
   use contact_system, only: contact_system_t, index_contact_equations
   use contact_dense, only: contact_dense_t, set_contact_springs
   use mumps_solver, only: mumps_solver_t
   implicit none
   private
   public :: mumps_schur_system_t

   type, extends(contact_system_t) :: mumps_schur_system_t
      integer :: nc = 0                      !! contact equations
      integer, allocatable :: ceq(:)         !! their global equation numbers
      integer, allocatable :: pos(:)         !! (neq) position of an equation in ceq, 0 if none
      integer, allocatable :: ppos(:, :)     !! (nd, npair) position of each
                                             !! pair dof in ceq, 0 if none
      integer, allocatable :: cdof(:, :)     !! (3, ndof) (dof, node, position)
                                             !! of the nodal dofs on c
      real(dp), allocatable :: kref(:, :, :) !! (nd, nd, npair) reference springs K_ref
      real(dp), allocatable :: dk(:, :, :)   !! (nd, nd, npair) K_c - K_ref of the current springs
      type(contact_dense_t) :: dense         !! S_ref = S + K_ref, and S_ref
                                             !! + K_c - K_ref factorized
      ! the attempt under way, and the steps whose recovery is postponed
      logical :: first = .true.              !! the next solve is the attempt's first
      logical :: postponed = .false.         !! some steps wait for their recovery
      real(dp), allocatable :: b1(:)         !! (neq) first right-hand side of the attempt
      real(dp), allocatable :: bsum(:)       !! (neq) sum of the postponed
                                             !! steps' first right-hand sides
      real(dp), allocatable :: xsum(:)       !! (n_c) sum of the attempt's dv_c
      real(dp), allocatable :: xpost(:)      !! (n_c) sum of the postponed steps' dv_c
      real(dp), allocatable :: xc(:)         !! (n_c) work
      real(dp), allocatable :: work(:)       !! (neq) work
      ! the last condensation by MUMPS, kept for proportional right-hand sides
      logical :: live = .false.              !! MUMPS holds the condensation of this attempt's b_1
      logical :: kept = .false.              !! cb and hc hold a condensation
      real(dp), allocatable :: cb(:)         !! (neq) its b_b (zero on c)
      real(dp), allocatable :: hc(:)         !! (n_c) its h(b_b) = g - b_c
   contains
      procedure :: prepare => schur_prepare
      procedure :: set_springs => schur_set_springs
      procedure :: begin_attempt => schur_begin_attempt
      procedure :: solve => schur_solve
      procedure :: recover => schur_recover
      procedure :: describe => schur_describe
      procedure :: memory_bytes => schur_memory
      procedure, private :: proportional => schur_proportional
      procedure :: scales_last => schur_scales_last
      procedure :: scale_last => schur_scale_last
   end type mumps_schur_system_t

contains

   !> The Schur complement of K_AB + K_ref onto the contact equations from
   !! MUMPS's factorization (the solver must be MUMPS).
   subroutine schur_prepare(this, kref, status)
      class(mumps_schur_system_t), intent(inout) :: this
      real(dp), intent(in) :: kref(:, :, :)
      type(status_t), intent(inout) :: status
      integer :: j
      this%condensed = .true.
      ! allocated explicitly: gfortran 12's reallocation on assignment reads the
      ! bounds of the unallocated component (UBSan: an integer overflow)
      if (allocated(this%kref)) deallocate (this%kref)
      allocate (this%kref, source=kref)
      allocate (this%dk, mold=kref)
      this%dk = 0.0_dp     ! the entries of no contact equation stay zero (set_contact_springs)
      call index_contact_equations(this%peq, this%neq, this%id, this%ceq, this%pos, this%ppos, &
                                   this%cdof)
      this%nc = size(this%ceq)
      if (this%nc < 1 .or. this%nc >= this%neq) then
         call status%set(STAT_SOLVER, &
                         'Schur contact system: needs between 1 and neq-1 contact equations, &
                         &has '// &
                         itoa(this%nc)//' of '//itoa(this%neq))
         return
      end if
      call this%dense%init(this%nc, size(this%peq, 1), size(this%peq, 2))
      select type (s => this%solver)
      type is (mumps_solver_t)
         call s%restore_base()
         do j = 1, size(this%peq, 2)
            call s%add_element(this%peq(:, j), kref(:, :, j))
         end do
         call s%factorize_schur(this%ceq, this%dense%s, status)
      class default
         call status%set(STAT_SOLVER, 'Schur contact system: needs the mumps solver, has '// &
                         s%name())
      end select
      if (.not. status%ok()) then
         status%message = 'Schur complement: the bodies with their contact equations held are &
         &singular or '// &
                          'the factorization failed ('//status%message//'); check the restraints'
         return
      end if
      call this%dense%prepare_projection(this%ppos, kref)
      allocate (this%b1(this%neq), this%bsum(this%neq), this%work(this%neq), this%xsum(this%nc), &
                this%xpost(this%nc), this%xc(this%nc), this%cb(this%neq), this%hc(this%nc))
      this%kept = .false.
      this%live = .false.
      this%bsum = 0.0_dp
      this%xpost = 0.0_dp
      this%postponed = .false.
   end subroutine schur_prepare

   !> S_ref + K_c - K_ref = S + K_c, factorized; a singular system is
   !! reported here, with its contact equation.
   subroutine schur_set_springs(this, kc, status)
      class(mumps_schur_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      call set_contact_springs(this%dense, this%ppos, this%ceq, kc, this%kref, this%dk, &
                               'the Schur complement', &
                               this%bad_eq, status)
   end subroutine schur_set_springs

   subroutine schur_begin_attempt(this)
      class(mumps_schur_system_t), intent(inout) :: this
      this%first = .true.
      this%xsum = 0.0_dp
   end subroutine schur_begin_attempt

   !> (K_AB + K_c) dv = b: dv at the dofs of the contact equations.
   subroutine schur_solve(this, b, du, status)
      class(mumps_schur_system_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)
      real(dp), intent(inout) :: du(:, :)
      type(status_t), intent(inout) :: status
      integer :: k
      real(dp) :: alpha
      logical :: reuse
      if (this%first) then
         this%b1 = b
         call this%proportional(b, alpha, reuse)
         if (reuse) then
            this%xc = b(this%ceq) + alpha*this%hc
            this%live = .false.
         else
            select type (s => this%solver)
            type is (mumps_solver_t)
               call s%schur_condense(b, this%xc, status)
            end select
            if (.not. status%ok()) return
            this%live = .true.
            this%cb = b
            this%cb(this%ceq) = 0.0_dp
            this%hc = this%xc - b(this%ceq)
            this%kept = .true.
         end if
         this%first = .false.
      else
         ! b is zero off the contact equations: g = b_c
         this%xc = b(this%ceq)
      end if
      call this%dense%solve(this%xc, status)
      if (.not. status%ok()) return
      if (this%dense%bad > 0) then
         this%bad_eq = this%ceq(this%dense%bad)
         call status%set(STAT_SINGULAR, 'zero pivot at contact equation '//itoa(this%bad_eq)// &
                         ' of the Schur complement')
         return
      end if
      this%xsum = this%xsum + this%xc
      do k = 1, size(this%cdof, 2)
         du(this%cdof(1, k), this%cdof(2, k)) = this%xc(this%cdof(3, k))
      end do
   end subroutine schur_solve

   pure logical function schur_scales_last(this)
      class(mumps_schur_system_t), intent(in) :: this
      associate (unused => this)
      end associate
      schur_scales_last = .true.
   end function schur_scales_last

   !> The last solve as alpha times itself: its dv_c in the attempt's sum (the
   !! expansion is linear in it); xc holds it until the next solve or recover.
   subroutine schur_scale_last(this, alpha)
      class(mumps_schur_system_t), intent(inout) :: this
      real(dp), intent(in) :: alpha
      this%xsum = this%xsum - (1.0_dp - alpha)*this%xc
      this%xc = alpha*this%xc
   end subroutine schur_scale_last

   !> The attempt's increment away from the contact equations: one expansion
   !! (or, postponed, the sum of several at the next need_full).
   subroutine schur_recover(this, du, need_full, status)
      class(mumps_schur_system_t), intent(inout) :: this
      real(dp), intent(inout) :: du(:, :)
      logical, intent(in) :: need_full
      type(status_t), intent(inout) :: status
      integer :: ip, idof, ieq
      if (this%first) return          ! no solve in this attempt: nothing to recover
      if (.not. need_full) then
         this%bsum = this%bsum + this%b1
         this%xpost = this%xpost + this%xsum
         this%postponed = .true.
         return
      end if
      select type (s => this%solver)
      type is (mumps_solver_t)
         if (this%postponed .or. .not. this%live) then
            ! condense the sum of the first right-hand sides (MUMPS holds none
            ! of them), expand with the sum of dv_c
            this%work = this%bsum + this%b1
            call s%schur_condense(this%work, this%xc, status)
            if (.not. status%ok()) return
            this%xc = this%xpost + this%xsum
         else
            this%xc = this%xsum
         end if
         call s%schur_expand(this%xc, this%work, status)
      end select
      if (.not. status%ok()) return
      this%bsum = 0.0_dp
      this%xpost = 0.0_dp
      this%postponed = .false.
      ! the dofs away from c; those on c hold the attempt's own sum already
      do ip = 1, size(this%id, 2)
         do idof = 1, 2
            ieq = this%id(idof, ip)
            if (ieq <= 0) cycle
            if (this%pos(ieq) == 0) du(idof, ip) = this%work(ieq)
         end do
      end do
   end subroutine schur_recover

   !> Whether the part of b away from the contact equations is alpha times
   !! the kept one (to 8 eps of its largest entry; a zero b_b is 0 times any).
   subroutine schur_proportional(this, b, alpha, yes)
      class(mumps_schur_system_t), intent(in) :: this
      real(dp), intent(in) :: b(:)
      real(dp), intent(out) :: alpha
      logical, intent(out) :: yes
      real(dp) :: bb, cc, bmax
      integer :: i
      yes = .false.
      alpha = 0.0_dp
      if (.not. this%kept) return
      bb = 0.0_dp
      cc = 0.0_dp
      bmax = 0.0_dp
      do i = 1, this%neq
         if (this%pos(i) /= 0) cycle
         bb = bb + b(i)*this%cb(i)
         cc = cc + this%cb(i)**2
         bmax = max(bmax, abs(b(i)))
      end do
      if (bmax == 0.0_dp) then
         yes = .true.
         return
      end if
      if (.not. cc > 0.0_dp) return
      alpha = bb/cc
      do i = 1, this%neq
         if (this%pos(i) /= 0) cycle
         if (.not. abs(b(i) - alpha*this%cb(i)) <= 8.0_dp*epsilon(1.0_dp)*bmax) return
      end do
      yes = .true.
   end subroutine schur_proportional

   function schur_describe(this) result(s)
      class(mumps_schur_system_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = 'Condensed    : bodies condensed onto '//itoa(this%nc)// &
          ' contact equations (MUMPS Schur complement of one sparse factorization'
      select type (sv => this%solver)
      type is (mumps_solver_t)
         if (len(sv%ordering_note()) > 0) s = s//', '//sv%ordering_note()
      end select
      s = s//')'
   end function schur_describe

   !> S and the factors of the contact equations, and the vectors.
   pure function schur_memory(this) result(bytes)
      class(mumps_schur_system_t), intent(in) :: this
      integer(i8) :: bytes
      bytes = this%dense%memory_bytes() + (4_i8*int(this%neq, i8) + 4_i8*int(this%nc, i8))*8_i8 + &
              4_i8*int(this%neq, i8)
      if (allocated(this%kref)) then
         bytes = bytes + 2_i8*storage_size(this%kref, i8)/8*size(this%kref, kind=i8)
      end if
   end function schur_memory
end module mumps_schur_system
