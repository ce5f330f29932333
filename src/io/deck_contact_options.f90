!> Readers of the CONTACT cards that set the contact algorithm's options for the whole
!! model (docs/deck-format.md, docs/contact.md): AUGMENTED, UPDATE/SCHEME, CONVERGE,
!! FIRSTINC, NEWCLOSED, REPEATS and START, stored in the contact specification's options.
module deck_contact_options
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t, shown
   use contact_types, only: contact_options_t, UPDATE_EXPLICIT, UPDATE_RETURN, NEWCLOSED_SECANT, &
                            NEWCLOSED_TANGENT
   use deck_contact_fields, only: check_tail
   implicit none
   private
   public :: read_augmented, read_update, read_converge, read_firstinc, read_newclosed, &
             read_repeats, read_start

contains

   !> AUGMENTED: penalty FACTOR (11-20) and TOL (21-30) of the ideal contact.
   subroutine read_augmented(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/AUGMENTED', 'FACTOR', v1, ok, default=100.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/AUGMENTED', 'TOL', v2, ok, default=1.0e-6_dp)
      call check_tail(d, ic, 31, 'FACTOR and TOL in columns 11-30', ok)
      if (.not. ok) return
      if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
         'CONTACT/AUGMENTED: FACTOR (columns 11-20) expected a positive penalty factor, found '// &
         rtoa(v1))
      if (.not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
         'CONTACT/AUGMENTED: TOL (columns 21-30) expected a tolerance in (0, 1) relative to '// &
         'the smallest contact element, found '//rtoa(v2))
      opts%aug_factor = v1
      opts%aug_tol = v2
   end subroutine read_augmented

   !> UPDATE or SCHEME (key): SCHEME INCREMENTAL (the paper) = UPDATE
   !! EXPLICIT; SCHEME NEWTON = UPDATE RETURN; SCHEME MODIFIED = RETURN with
   !! the stiffness kept (modified Newton).
   subroutine read_update(d, ic, key, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      character(len=*), intent(in) :: key    !! UPDATE or SCHEME, for messages
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/'//key, key, w, ok)
      select case (w)
      case ('EXPLICIT', 'INCREMENTA')
         opts%update = UPDATE_EXPLICIT
         opts%modified = .false.
      case ('RETURN', 'NEWTON')
         opts%update = UPDATE_RETURN
         opts%modified = .false.
      case ('MODIFIED')
         opts%update = UPDATE_RETURN
         opts%modified = .true.
      case default
         if (ok) call d%error_at(ic, 11, 'E-CONTACT', 'CONTACT/'//key// &
            ' (columns 11-20) expected INCREMENTAL (or EXPLICIT), NEWTON (or RETURN) or '// &
            'MODIFIED, found "'//w//'"')
      end select
   end subroutine read_update

   !> CONVERGE: relative force TOLR (11-20) and displacement TOLU (21-30) tolerances.
   subroutine read_converge(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/CONVERGE', 'TOLR', v1, ok, default=1.0e-10_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/CONVERGE', 'TOLU', v2, ok, default=1.0e-8_dp)
      call check_tail(d, ic, 31, 'TOLR, TOLU in columns 11-30', ok)
      if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
         'CONTACT/CONVERGE: TOLR (columns 11-20) expected a relative force tolerance in (0, '// &
         '1), found '//rtoa(v1))
      if (ok .and. .not. (v2 > 0.0_dp .and. v2 < 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
         'CONTACT/CONVERGE: TOLU (columns 21-30) expected a relative displacement tolerance in '// &
         '(0, 1), found '//rtoa(v2))
      if (ok) then
         opts%tol_residual = v1
         opts%tol_displacement = v2
      end if
   end subroutine read_converge

   !> FIRSTINC: SECANT or ITERATE (11-20), the rule of the first increment.
   subroutine read_firstinc(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/FIRSTINC', 'RULE', w, ok)
      if (w == 'SECANT') then
         opts%first_iterate = .false.
      else if (w == 'ITERATE') then
         opts%first_iterate = .true.
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/FIRSTINC (columns 11-20) expected SECANT or ITERATE, found "'//w//'"')
      end if
   end subroutine read_firstinc

   !> NEWCLOSED: SECANT or TANGENT (11-20) and PMIN (21-30), a fraction of p_m.
   subroutine read_newclosed(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      character(len=:), allocatable :: w
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/NEWCLOSED', 'RULE', w, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/NEWCLOSED', 'PMIN', v1, ok, default=1.0e-3_dp)
      call check_tail(d, ic, 31, 'SECANT or TANGENT and PMIN in columns 11-30', ok)
      if (ok .and. w == 'SECANT') then
         opts%newly_closed = NEWCLOSED_SECANT
      else if (ok .and. w == 'TANGENT') then
         opts%newly_closed = NEWCLOSED_TANGENT
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/NEWCLOSED (columns 11-20) expected SECANT or TANGENT, found "'//w//'"')
      end if
      if (ok .and. .not. (v1 > 0.0_dp .and. v1 < 1.0_dp)) then
         call d%error_at(ic, 21, 'E-CONTACT', &
            'CONTACT/NEWCLOSED: PMIN (columns 21-30) expected the floor pressure as a fraction '// &
            'of p_m in (0, 1), found '//rtoa(v1))
      else if (ok) then
         opts%p_min_ratio = v1
      end if
   end subroutine read_newclosed

   !> REPEATS: MAXREP (11-20), the cap on repeats of one increment.
   subroutine read_repeats(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      integer :: iv
      logical :: ok
      ok = .true.
      call d%get_int(ic, 11, 20, 'CONTACT/REPEATS', 'MAXREP', iv, ok)
      call check_tail(d, ic, 21, 'MAXREP in columns 11-20', ok)
      if (ok .and. (iv < 1 .or. iv > 10000)) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/REPEATS (columns 11-20) expected 1..10000, found '//itoa(iv))
      else if (ok) then
         opts%max_repeats = iv
         opts%repeats_given = .true.
      end if
   end subroutine read_repeats

   !> START: starting pressure PM (11-20) [model stress], NSTART (21-30) and
   !! GAPTOL (31-40) [model length].
   subroutine read_start(d, ic, opts)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(contact_options_t), intent(inout) :: opts
      real(dp) :: v1, v2
      integer :: iv
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/START', 'PM', v1, ok, default=-1.0_dp)
      call d%get_int(ic, 21, 30, 'CONTACT/START', 'NSTART', iv, ok, default=0)
      call d%get_real(ic, 31, 40, 'CONTACT/START', 'GAPTOL', v2, ok, default=-1.0_dp)
      call check_tail(d, ic, 41, 'PM, NSTART, GAPTOL in columns 11-40', ok)
      if (.not. ok) return
      if (len_trim(d%field_text(ic, 11, 20)) > 0 .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, &
         11, 'E-CONTACT', 'CONTACT/START: PM (columns 11-20) expected a positive starting '// &
         'pressure, found '//rtoa(v1))
      if (iv < 0) call d%error_at(ic, 21, 'E-CONTACT', &
         'CONTACT/START: NSTART (columns 21-30) expected a number of pairs >= 0, found '// &
         itoa(iv))
      opts%p_start = v1
      opts%n_start = iv
      opts%gap_tol = v2
   end subroutine read_start
end module deck_contact_options
