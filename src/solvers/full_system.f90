!> The full system: K_AB + K_c refactorized by a linear solver for every new
!! set of springs (the paper's path, and the one for many contact equations).
!!
!! `set_springs` puts the base K_AB back, adds the spring matrices and
!! factorizes; `solve` is one solve with those factors and gives the whole
!! displacement field at once, so `recover` has nothing left to do.  Works on
!! any `linear_solver_t` (skyline, UMFPACK, dense), and on a model without
!! contact (no springs: K_AB alone).
module full_system
   use kinds, only: dp, i8
   use errors, only: status_t
   use contact_system, only: contact_system_t
   implicit none
   private
   public :: full_system_t

   type, extends(contact_system_t) :: full_system_t
   contains
      procedure :: prepare => full_prepare
      procedure :: set_springs => full_set_springs
      procedure :: begin_attempt => full_begin_attempt
      procedure :: solve => full_solve
      procedure :: recover => full_recover
      procedure :: describe => full_describe
      procedure :: memory_bytes => full_memory
      procedure :: scales_last => full_scales_last
   end type full_system_t

contains

   !> Nothing to prepare: the base K_AB is in the solver.  With contact
   !! pairs the solver is told that it will factorize the pattern once per
   !! set of springs (the MUMPS solver may then order it by METIS).
   subroutine full_prepare(this, kref, status)
      class(full_system_t), intent(inout) :: this
      real(dp), intent(in) :: kref(:, :, :)
      type(status_t), intent(inout) :: status
      this%condensed = .false.
      if (allocated(this%solver) .and. allocated(this%peq)) then
         if (size(this%peq, 2) > 0) call this%solver%expect_refactorizations()
      end if
      associate (unused => kref, unused2 => status)
      end associate
   end subroutine full_prepare

   !> K_AB + K_c, factorized (a zero pivot: STAT_SINGULAR, the solver knows its equation).
   subroutine full_set_springs(this, kc, status)
      class(full_system_t), intent(inout) :: this
      real(dp), intent(in) :: kc(:, :, :)
      type(status_t), intent(inout) :: status
      integer :: j
      this%bad_eq = 0
      call this%solver%restore_base()
      do j = 1, size(this%peq, 2)
         call this%solver%add_element(this%peq(:, j), kc(:, :, j))
      end do
      call this%solver%factorize(status)
   end subroutine full_set_springs

   subroutine full_begin_attempt(this)
      class(full_system_t), intent(inout) :: this
      associate (unused => this)
      end associate
   end subroutine full_begin_attempt

   !> One solve with the current factors; every free dof of du gets its value.
   subroutine full_solve(this, b, du, status)
      class(full_system_t), intent(inout) :: this
      real(dp), intent(inout) :: b(:)
      real(dp), intent(inout) :: du(:, :)
      type(status_t), intent(inout) :: status
      integer :: ip, idof
      call this%solver%solve(b, status)
      if (.not. status%ok()) return
      do ip = 1, size(this%id, 2)
         do idof = 1, 2
            if (this%id(idof, ip) > 0) du(idof, ip) = b(this%id(idof, ip))
         end do
      end do
   end subroutine full_solve

   !> The solutions are complete in du: a scaled last solve needs nothing kept here.
   pure logical function full_scales_last(this)
      class(full_system_t), intent(in) :: this
      associate (unused => this)
      end associate
      full_scales_last = .true.
   end function full_scales_last

   !> The solutions were complete: du is the increment already.
   subroutine full_recover(this, du, need_full, status)
      class(full_system_t), intent(inout) :: this
      real(dp), intent(inout) :: du(:, :)
      logical, intent(in) :: need_full
      type(status_t), intent(inout) :: status
      associate (unused => this, unused2 => du, unused3 => need_full, unused4 => status)
      end associate
   end subroutine full_recover

   function full_describe(this) result(s)
      class(full_system_t), intent(in) :: this
      character(len=:), allocatable :: s
      s = ''
      if (.not. allocated(this%solver)) return
      s = this%solver%ordering_note()
      if (len(s) > 0) s = 'Ordering     : '//s//' of the sparse factorization'
   end function full_describe

   pure function full_memory(this) result(bytes)
      class(full_system_t), intent(in) :: this
      integer(i8) :: bytes
      bytes = 0
      associate (unused => this)
      end associate
   end function full_memory
end module full_system
