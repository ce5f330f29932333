!> Pretension sections in the increment loop: the lock, and the force
!! across each section after a step.
!!
!! A section is force-controlled through the load case of its card (the
!! reference node carries -F lambda along the axis).  In an increment that
!! holds that case's factor, a LOCK section keeps its shortening (the mean
!! closure of its nodes and their copies, section_shortening): the force on
!! the reference node then is whatever holds it, found by a chord iteration on the increment
!! -- attempt with the extra forces x (first those of the last locked
!! increment), measure the shortening's increments r(x), update x <- x - J^-1 r
!! with the Jacobian of r (by one probe per locked section, kept for the next
!! increments) until |r| is round-off of the model's size.  The bodies are
!! linear and the contact laws piecewise smooth, so without state changes r is
!! affine in x and one update is exact; every attempt starts from the
!! committed state, and the step's solutions count those of all attempts.
!!
!! In a locked increment each locked section's reference node is also held in
!! the matrix by a spring to ground (hold_references: stiffness kground, the sum
!! of the section's springs, put into the solver's base and taken out again when
!! the section's force is changed).  Without it the reference node is free, and
!! once the clamped parts separate the bolt's part beyond the cut is joined to
!! the rest only through the section: a mechanism (a singular system).  The
!! spring does not decide the lock -- the chord iteration on x does, whatever
!! kground -- and its reaction -kground du_r is a holding force like x: both go
!! into fext_new at the reference node, so that the springs across the section
!! carry exactly the forces on it (the force balance of the step).
module pretension_control
   use kinds, only: dp
   use errors, only: status_t, STAT_NO_CONVERGENCE
   use strings, only: itoa, rtoa
   use model, only: model_t
   use pretension, only: PRETENSION_LOCK
   use pretension_assembly, only: section_shortening
   use contact_algorithm, only: contact_state_t
   use increment_attempt, only: analysis_t, attempt_t, attempt_increment
   implicit none
   private
   public :: attempt_with_pretension, MAX_LOCK_ITER, locked_sections, hold_references, solve_small

   integer, parameter :: MAX_LOCK_ITER = 12    !! chord updates of one increment's lock

contains

   !> attempt_increment, with the LOCK sections whose case is held kept at
   !! their opening (fext_new gets the forces that hold them), and every
   !! section whose force the increment changes released from the holding
   !! forces of its earlier locked increments (release_holding).
   subroutine attempt_with_pretension(an, m, st, dlam, carry, fext_new, first, att, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:), carry(:)
      real(dp), intent(inout) :: fext_new(:, :)
      logical, intent(in) :: first
      type(attempt_t), intent(inout) :: att
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: cm(:), fin(:)
      integer :: k
      if (an%pret%n == 0) then
         call attempt_locked(an, m, st, dlam, carry, fext_new, first, att, status)
         return
      end if
      cm = carry
      allocate (fin(an%pret%n))
      call release_holding(an, m, dlam, cm, fext_new, fin)
      call attempt_locked(an, m, st, dlam, cm, fext_new, first, att, status)
      do k = 1, an%pret%n
         associate (p => m%pretensions(k))
            an%pret%fref_out(k) = fext_new(p%axis, p%ref)
            an%pret%hsum_out(k) = an%pret%hsum(k) + fext_new(p%axis, p%ref) - fin(k)
         end associate
      end do
      an%pret%tried = .true.
   end subroutine attempt_with_pretension

   !> The holding forces of a LOCK section's locked increments (the chord
   !! iteration's x and the ground spring's reaction) are external forces on
   !! its reference node and stay in the committed loads.  An increment that
   !! changes the section's force (its case's factor) gives it F lambda again
   !! (docs/bolts.md): their sum is taken off the reference node, in the loads
   !! and as an out-of-balance force of the increment.  Without it a preload
   !! released to zero after a locked stage kept the change of the bolt force
   !! that the lock had brought (a joint diagram's hysteresis: 7.3 N of 20 kN
   !! in a bolted joint, tests/decks/bolt/release_zero), and the bolt pulled
   !! its head off the clamped plate at zero preload.  Which attempt was
   !! accepted is read from the loads: the committed reference force is the
   !! one the last attempt left when the increment's loads are that attempt's
   !! plus this increment's, to round-off (else it was cut, and the sum
   !! committed before it stays).  fin: the reference nodes' forces before
   !! the release.
   subroutine release_holding(an, m, dlam, cm, fext_new, fin)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: dlam(:)
      real(dp), intent(inout) :: cm(:), fext_new(:, :)
      real(dp), intent(out) :: fin(:)
      real(dp) :: fcommitted, finc, h
      integer :: k, ieq
      do k = 1, an%pret%n
         associate (p => m%pretensions(k))
            finc = sum(dlam*an%fcase(p%axis, p%ref, :))
            fcommitted = fext_new(p%axis, p%ref) - finc
            if (an%pret%tried) then
               if (abs(fcommitted - an%pret%fref_out(k)) <= 1.0e-13_dp* &
                   max(abs(fext_new(p%axis, p%ref)), abs(finc), abs(an%pret%fref_out(k)))) then
                  an%pret%hsum(k) = an%pret%hsum_out(k)
               end if
            end if
            h = an%pret%hsum(k)
            fin(k) = fext_new(p%axis, p%ref)
            if (p%mode == PRETENSION_LOCK .and. abs(dlam(p%icase)) > 0.0_dp .and. &
                abs(h) > 0.0_dp) then
               ieq = an%map%id(p%axis, p%ref)
               fext_new(p%axis, p%ref) = fext_new(p%axis, p%ref) - h
               if (ieq > 0) cm(ieq) = cm(ieq) - h
            end if
         end associate
      end do
   end subroutine release_holding

   !> attempt_increment, with the LOCK sections whose case is held kept at
   !! their opening; fext_new gets the forces that hold them.
   subroutine attempt_locked(an, m, st, dlam, carry, fext_new, first, att, status)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      type(contact_state_t), intent(inout) :: st
      real(dp), intent(in) :: dlam(:), carry(:)
      real(dp), intent(inout) :: fext_new(:, :)     !! external forces after the
                                                    !! step; + the holding forces
      logical, intent(in) :: first
      type(attempt_t), intent(inout) :: att
      type(status_t), intent(inout) :: status
      integer, allocatable :: lk(:)
      real(dp), allocatable :: x(:), r(:), r0(:), jac(:, :), f0(:, :)
      real(dp) :: h, tol, scale
      integer :: j, it, n, spent

      allocate (lk(0))      ! (gfortran 12 warns of an unset descriptor without it)
      lk = locked_sections(m, dlam)
      call hold_references(an, m, lk)
      n = size(lk)
      if (n == 0) then
         call attempt_increment(an, m, st, dlam, carry, fext_new, first, att, status)
         return
      end if
      f0 = fext_new
      allocate (x(n), r(n), r0(n), jac(n, n))
      scale = max(maxval(abs(fext_new)), an%force_scale, tiny(1.0_dp))
      h = 1.0e-3_dp*scale
      ! the opening is kept to round-off of the model's lengths (1e-13 of its size:
      ! about 1e-10 of a bolt's elongation, below the solution's own accuracy)
      tol = 1.0e-13_dp*max(maxval(abs(m%coord)), tiny(1.0_dp))
      spent = 0
      ! the first guess: the holding forces of the sections' last locked increments (equal load
      ! steps need equal holding forces), then chord updates with the last Jacobian; probes for a
      ! new Jacobian at the first lock and when the old one does not converge in two updates
      x = an%pret%x_last(lk)
      call try(x, r)
      if (.not. status%ok() .or. done(r)) return
      if (an%pret%have_jac) then
         jac = an%pret%jac(lk, lk)
         do it = 1, 2
            x = x - solve_small(jac, r)
            call try(x, r)
            if (.not. status%ok() .or. done(r)) return
         end do
      end if
      do j = 1, n
         r0 = r
         x(j) = x(j) + h
         call try(x, r)
         if (.not. status%ok()) return
         jac(:, j) = (r - r0)/h
         x(j) = x(j) - h
         r = r0
      end do
      an%pret%jac(lk, lk) = jac
      an%pret%have_jac = .true.
      do it = 1, MAX_LOCK_ITER
         x = x - solve_small(jac, r)
         call try(x, r)
         if (.not. status%ok() .or. done(r)) return
      end do
      call status%set(STAT_NO_CONVERGENCE, &
                      'the locked pretension section(s) did not keep their opening: '// &
                      'it changed by '//rtoa(maxval(abs(r)))//' after '//itoa(MAX_LOCK_ITER)// &
                      ' chord updates')
   contains
      !> One attempt with the extra forces xx on the locked reference nodes.
      subroutine try(xx, rr)
         real(dp), intent(in) :: xx(:)
         real(dp), intent(out) :: rr(:)
         real(dp), allocatable :: cm(:)
         integer :: q, ieq
         allocate (cm(size(carry)))
         cm = carry
         fext_new = f0
         do q = 1, n
            associate (p => m%pretensions(lk(q)))
               ieq = an%map%id(p%axis, p%ref)
               cm(ieq) = cm(ieq) + xx(q)
               fext_new(p%axis, p%ref) = fext_new(p%axis, p%ref) + xx(q)
            end associate
         end do
         call attempt_increment(an, m, st, dlam, cm, fext_new, first, att, status)
         ! the step's solutions are those of all its attempts
         spent = spent + att%solutions
         att%solutions = spent
         an%pret%x_last(lk) = xx
         rr = 0.0_dp
         if (.not. status%ok()) return
         do q = 1, n
            ! the ground spring's reaction: a holding force on the reference node
            associate (p => m%pretensions(lk(q)))
               fext_new(p%axis, p%ref) = fext_new(p%axis, p%ref) &
                                         - an%pret%kground(lk(q))*att%du(p%axis, p%ref)
            end associate
            rr(q) = section_shortening(m%pretensions(lk(q)), an%pret%sections(lk(q))%w, att%du)
         end do
      end subroutine try
      logical function done(rr)
         real(dp), intent(in) :: rr(:)
         done = maxval(abs(rr)) <= tol
      end function done
   end subroutine attempt_locked

   !> The LOCK sections whose case's factor the increment holds (dlam 0).
   pure function locked_sections(m, dlam) result(lk)
      type(model_t), intent(in) :: m
      real(dp), intent(in) :: dlam(:)
      integer, allocatable :: lk(:)
      integer :: k
      lk = [integer ::]
      if (.not. allocated(m%pretensions)) return
      do k = 1, size(m%pretensions)
         associate (p => m%pretensions(k))
            if (p%mode == PRETENSION_LOCK .and. .not. (abs(dlam(p%icase)) > 0.0_dp)) lk = [lk, k]
         end associate
      end do
   end function locked_sections

   !> Hold the reference nodes of the sections lk (and only those) in the matrix:
   !! a spring to ground of stiffness kground on each one's axial equation, put
   !! into (or taken out of) the solver's base when the set changes; the system
   !! is then refactorized at the next solution.
   subroutine hold_references(an, m, lk)
      type(analysis_t), intent(inout) :: an
      type(model_t), intent(in) :: m
      integer, intent(in) :: lk(:)
      logical, allocatable :: want(:)
      real(dp) :: ke(1, 1)
      integer :: k
      if (an%pret%n == 0) return
      allocate (want(an%pret%n))
      want = .false.
      want(lk) = .true.
      if (all(want .eqv. an%pret%held)) return
      call an%sys%solver%restore_base()
      do k = 1, an%pret%n
         if (want(k) .eqv. an%pret%held(k)) cycle
         ke = merge(1.0_dp, -1.0_dp, want(k))*an%pret%kground(k)
         associate (p => m%pretensions(k))
            call an%sys%solver%add_element([an%map%id(p%axis, p%ref)], ke)
         end associate
      end do
      call an%sys%solver%store_base()
      an%pret%held = want
      an%system_current = .false.
   end subroutine hold_references

   !> x with a x = b for a small dense a (Gaussian elimination, partial pivoting).
   pure function solve_small(a, b) result(x)
      real(dp), intent(in) :: a(:, :), b(:)
      real(dp) :: x(size(b)), w(size(b), size(b) + 1), t(size(b) + 1)
      integer :: i, k, p, n
      n = size(b)
      w(:, 1:n) = a
      w(:, n + 1) = b
      do k = 1, n
         p = k - 1 + maxloc(abs(w(k:n, k)), 1)
         t = w(k, :)
         w(k, :) = w(p, :)
         w(p, :) = t
         if (.not. (abs(w(k, k)) > 0.0_dp)) then
            x = 0.0_dp
            return
         end if
         do i = k + 1, n
            w(i, :) = w(i, :) - w(i, k)/w(k, k)*w(k, :)
         end do
      end do
      do i = n, 1, -1
         x(i) = (w(i, n + 1) - sum(w(i, i + 1:n)*x(i + 1:n)))/w(i, i)
      end do
   end function solve_small
end module pretension_control
