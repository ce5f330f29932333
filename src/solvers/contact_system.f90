!> The contact system: what an increment needs of the system [K_AB + K_c] dv = b
!! it solves, whatever the way it is solved.
!!
!! The bodies' stiffness K_AB is constant (linear elastic, small strain, eq.
!! 4.12); only the contact springs K_c change, and they act on the contact
!! equations (the free equations of the pairs' dofs).  An implementation
!! decides how to exploit that: refactorize the whole system for every new set
!! of springs (full_system), condense the bodies onto the contact equations
!! once (condensed_system), or take the Schur complement from one sparse
!! factorization (a MUMPS implementation).  The driver holds a
!! class(contact_system_t) chosen once by `create_contact_system`
!! (contact_system_factory) and never asks which one it holds.
!!
!! Life cycle, the same for every implementation:
!!
!!     call create_contact_system(condense, npair, nc, sys)   ! the factory, once
!!     ! K_AB assembled into a linear solver and kept as its base (store_base)
!!     call sys%setup(solver, map, peq, kref, status)  ! once: takes the solver over
!!     do attempt at an increment
!!        call sys%begin_attempt()                      ! a new displacement increment
!!        do solution
!!           call sys%set_springs(kc, status)           ! when the springs' modes changed
!!           call sys%solve(b, du, status)              ! b: first any vector, later only
!!        end do                                        !    spring forces (see below)
!!        call sys%recover(du, need_full, status)       ! accepted: the full increment
!!     end do
!!     call sys%free()
!!
!! Contract of the calls:
!! * `setup` receives the solver with K_AB assembled and stored as its base,
!!   the dof map, the equations of every pair's dofs `peq(nd, npair)` (<= 0:
!!   restrained, or beyond the pair's 2 nn dofs) and reference springs
!!   `kref(nd, nd, npair)` of the bodies' stiffness scale, which an
!!   implementation that factorizes the bodies alone may add to keep them
!!   regular where the springs are their only support (the others ignore them).
!! * `set_springs(kc)` takes the spring matrices of the current modes, pair by
!!   pair in the order of `peq`.  A singular system may be reported here or by
!!   the next `solve` (STAT_SINGULAR); `failed_equation()` then names the
!!   equation of the singular pivot.
!! * `solve(b, du)`: b (neq) is the right-hand side, overwritten (work space).
!!   The solution goes to the free dofs of du (2, npoin): it is exact at every
!!   dof of a contact equation; an implementation that defers the rest to
!!   `recover` leaves the other dofs as they are (the caller passes zeros), the
!!   full system sets them all.  Restrained dofs are never touched.  The first
!!   solve after `begin_attempt` takes any right-hand side; every later one of
!!   the same attempt is zero off the contact equations (out-of-balance spring
!!   forces), which an implementation may exploit.
!! * `recover(du, need_full)`: on entry du holds the sum of the attempt's
!!   solutions as `solve` returned them; on exit every free dof holds the
!!   displacement increment of the attempt.  Call it once for an accepted
!!   attempt.  With need_full = .false. the caller does not need the dofs away
!!   from the contact equations for this step (its fields are not written) and
!!   an implementation may postpone that work, keeping what it needs to add it
!!   to the next recover with need_full = .true. (mumps_schur_system does;
!!   full_system has nothing to recover, condensed_system recovers always).
!!   The driver passes .false. for the steps of a contact run that are neither
!!   written nor listed nor the last.
!! * `scale_last(alpha)`, where `scales_last()` is true: the last solve (not the
!!   attempt's first) counts as alpha times its solution (a line search that
!!   shortened the step, increment_attempt): the caller scales the contact dofs
!!   of du itself; the system scales what it keeps for `recover`.  A system that
!!   cannot (the default) is never asked.
module contact_system
   use kinds, only: dp, i8
   use errors, only: status_t
   use linear_solver, only: linear_solver_t
   use dof_map, only: dof_map_t
   implicit none
   private
   public :: contact_system_t, contact_equations, index_contact_equations

   type, abstract :: contact_system_t
      class(linear_solver_t), allocatable :: solver   !! the bodies' solver (K_AB its
                                                      !! base), owned after setup
      integer :: neq = 0                              !! equations
      integer, allocatable :: id(:, :)                !! (2, npoin) equation of each
                                                      !! nodal dof (dof_map%id)
      integer, allocatable :: peq(:, :)               !! (nd, npair) equations of the pairs' dofs
      integer :: bad_eq = 0                           !! equation of a singular pivot
                                                      !! found by the system itself
      logical :: condensed = .false.                  !! the bodies are condensed
                                                      !! onto the contact equations
      integer, allocatable :: support(:)              !! (npair) optional, set before
                                                      !! set_springs: the springs of
                                                      !! each pair (bit 0: K_n > 0,
                                                      !! bit 1: K_T > 0)
   contains
      procedure :: setup
      procedure(prepare_i), deferred :: prepare
      procedure(set_springs_i), deferred :: set_springs
      procedure(begin_attempt_i), deferred :: begin_attempt
      procedure(solve_i), deferred :: solve
      procedure(recover_i), deferred :: recover
      procedure(describe_i), deferred :: describe
      procedure(memory_i), deferred :: memory_bytes
      procedure :: failed_equation
      procedure :: free
      procedure :: scales_last
      procedure :: scale_last
   end type contact_system_t

   abstract interface
      !> The implementation's part of `setup`: everything done once, after the
      !! common part (solver, id, peq and neq are set).
      subroutine prepare_i(this, kref, status)
         import :: contact_system_t, dp, status_t
         class(contact_system_t), intent(inout) :: this
         real(dp), intent(in) :: kref(:, :, :)     !! (nd, nd, npair) reference springs
         type(status_t), intent(inout) :: status
      end subroutine prepare_i

      !> The spring matrices of the current modes.
      subroutine set_springs_i(this, kc, status)
         import :: contact_system_t, dp, status_t
         class(contact_system_t), intent(inout) :: this
         real(dp), intent(in) :: kc(:, :, :)       !! (nd, nd, npair) in the order of peq
         type(status_t), intent(inout) :: status
      end subroutine set_springs_i

      subroutine begin_attempt_i(this)
         import :: contact_system_t
         class(contact_system_t), intent(inout) :: this
      end subroutine begin_attempt_i

      !> Solve for b; the solution into the free dofs of du (see the contract).
      subroutine solve_i(this, b, du, status)
         import :: contact_system_t, dp, status_t
         class(contact_system_t), intent(inout) :: this
         real(dp), intent(inout) :: b(:)           !! (neq) right-hand side, overwritten
         real(dp), intent(inout) :: du(:, :)       !! (2, npoin) solution at the free dofs
         type(status_t), intent(inout) :: status
      end subroutine solve_i

      !> The full displacement increment of the accepted attempt in du.
      subroutine recover_i(this, du, need_full, status)
         import :: contact_system_t, dp, status_t
         class(contact_system_t), intent(inout) :: this
         real(dp), intent(inout) :: du(:, :)       !! (2, npoin) the attempt's increment
         logical, intent(in) :: need_full          !! the dofs away from the contact
                                                   !! equations are needed now
         type(status_t), intent(inout) :: status
      end subroutine recover_i

      !> One line for the header of the listing and the terminal ('' for none).
      function describe_i(this) result(s)
         import :: contact_system_t
         class(contact_system_t), intent(in) :: this
         character(len=:), allocatable :: s
      end function describe_i

      !> Memory held by the system beyond its linear solver [bytes].
      pure function memory_i(this) result(bytes)
         import :: contact_system_t, i8
         class(contact_system_t), intent(in) :: this
         integer(i8) :: bytes
      end function memory_i
   end interface

contains

   !> Take the bodies' solver over and prepare what stays fixed for the run.
   subroutine setup(this, solver, map, peq, kref, status)
      class(contact_system_t), intent(inout) :: this
      class(linear_solver_t), allocatable, intent(inout) :: solver   !! K_AB stored as
         !! base; moved in
      type(dof_map_t), intent(in) :: map
      integer, intent(in) :: peq(:, :)            !! (nd, npair) equations of the pairs' dofs
      real(dp), intent(in) :: kref(:, :, :)       !! (nd, nd, npair) reference springs
      type(status_t), intent(inout) :: status
      call move_alloc(solver, this%solver)
      this%neq = map%neq
      this%id = map%id
      this%peq = peq
      this%bad_eq = 0
      call this%prepare(kref, status)
   end subroutine setup

   !> Equation of the singular pivot of the last failure (0 if unknown).
   pure integer function failed_equation(this) result(eq)
      class(contact_system_t), intent(in) :: this
      eq = this%bad_eq
      if (eq <= 0 .and. allocated(this%solver)) eq = this%solver%failed_equation()
   end function failed_equation

   !> Release the solver and the system's storage.
   subroutine free(this)
      class(contact_system_t), intent(inout) :: this
      if (allocated(this%solver)) then
         call this%solver%free()
         deallocate (this%solver)
      end if
      if (allocated(this%id)) deallocate (this%id)
      if (allocated(this%peq)) deallocate (this%peq)
   end subroutine free

   !> The distinct free equations of the pairs' dofs, sorted.
   pure function contact_equations(peq, neq) result(c)
      integer, intent(in) :: peq(:, :)            !! (nd, npair)
      integer, intent(in) :: neq
      integer, allocatable :: c(:)
      logical, allocatable :: mark(:)
      integer :: j, k
      allocate (mark(neq))
      mark = .false.
      do j = 1, size(peq, 2)
         do k = 1, size(peq, 1)
            if (peq(k, j) > 0) mark(peq(k, j)) = .true.
         end do
      end do
      c = pack([(k, k=1, neq)], mark)
   end function contact_equations
   !> Whether the system can scale its last solve (scale_last): not by default.
   pure logical function scales_last(this)
      class(contact_system_t), intent(in) :: this
      associate (unused => this)
      end associate
      scales_last = .false.
   end function scales_last

   !> The last solve counts as alpha times its solution (never called where
   !! scales_last is false).
   subroutine scale_last(this, alpha)
      class(contact_system_t), intent(inout) :: this
      real(dp), intent(in) :: alpha
      associate (unused => this, unused2 => alpha)
      end associate
   end subroutine scale_last

   !> Where the contact equations sit, for the systems that condense onto
   !! them: ceq the distinct free equations of the pairs (sorted), pos (neq)
   !! the position of an equation in ceq (0 if none), ppos (nd, npair) the
   !! position of each pair dof (0 if none), cdof (3, n) (dof, node, position)
   !! of the nodal dofs whose equation is a contact equation.
   pure subroutine index_contact_equations(peq, neq, id, ceq, pos, ppos, cdof)
      integer, intent(in) :: peq(:, :)            !! (nd, npair)
      integer, intent(in) :: neq
      integer, intent(in) :: id(:, :)             !! (2, npoin) equation of each nodal dof
      integer, allocatable, intent(out) :: ceq(:), pos(:), ppos(:, :), cdof(:, :)
      integer :: j, k, ip, idof, n
      ceq = contact_equations(peq, neq)
      allocate (pos(neq), ppos(size(peq, 1), size(peq, 2)))
      pos = 0
      do k = 1, size(ceq)
         pos(ceq(k)) = k
      end do
      ppos = 0
      do j = 1, size(peq, 2)
         do k = 1, size(peq, 1)
            if (peq(k, j) > 0) ppos(k, j) = pos(peq(k, j))
         end do
      end do
      n = 0
      do ip = 1, size(id, 2)
         do idof = 1, 2
            if (id(idof, ip) > 0) then
               if (pos(id(idof, ip)) > 0) n = n + 1
            end if
         end do
      end do
      allocate (cdof(3, n))
      n = 0
      do ip = 1, size(id, 2)
         do idof = 1, 2
            if (id(idof, ip) <= 0) cycle
            if (pos(id(idof, ip)) == 0) cycle
            n = n + 1
            cdof(:, n) = [idof, ip, pos(id(idof, ip))]
         end do
      end do
   end subroutine index_contact_equations
end module contact_system
