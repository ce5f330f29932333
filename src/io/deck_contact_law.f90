!> Readers of the CONTACT cards that define an interface's law (docs/deck-format.md,
!! docs/contact.md): LAW, UNITS, NORMAL, TANGENT, FRICTION, HARDENING, SLIP and TOLERANCE.
!! Each checks its own fields and stores the constants in the deck's units in the
!! interface's specification (model/contact_spec); the conversions come after reading
!! (contact/contact_definition).
module deck_contact_law
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t, shown
   use contact_types, only: interface_t, LAW_ROUGH, LAW_IDEAL, FRICTION_NONE, FRICTION_COULOMB, &
                            FRICTION_FREDRIKSSON, UNITS_KGF_UM, UNITS_N_UM, UNITS_MODEL, &
                            SLIP_IRREVERSIBLE, SLIP_GROSS
   use contact_spec, only: iface_spec_t
   use deck_contact_fields, only: check_tail
   implicit none
   private
   public :: read_law, read_units, read_normal, read_tangent, read_friction, read_hardening, &
             read_slip, read_tolerance

contains

   !> LAW: ROUGH or IDEAL (11-20).
   subroutine read_law(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/LAW', 'LAW', w, ok)
      if (w == 'ROUGH') then
         law%law = LAW_ROUGH
      else if (w == 'IDEAL') then
         law%law = LAW_IDEAL
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/LAW (columns 11-20) expected ROUGH or IDEAL, found "'//w//'"')
      end if
   end subroutine read_law

   !> UNITS: KGF_UM, N_UM or MODEL (11-20), the units of CN and R.
   subroutine read_units(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/UNITS', 'UNITS', w, ok)
      select case (w)
      case ('KGF_UM')
         law%units = UNITS_KGF_UM
      case ('N_UM')
         law%units = UNITS_N_UM
      case ('MODEL')
         law%units = UNITS_MODEL
      case default
         if (ok) call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/UNITS (columns 11-20) expected KGF_UM, N_UM or MODEL, found "'//w//'"')
      end select
   end subroutine read_units

   !> NORMAL: CN, M (loading) and CN2, M2 (unloading; default CN/2, M), in
   !! the interface's UNITS.
   subroutine read_normal(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      real(dp) :: v1, v2, v3, v4
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/NORMAL', 'CN', v1, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/NORMAL', 'M', v2, ok)
      call d%get_real(ic, 31, 40, 'CONTACT/NORMAL', 'CN2', v3, ok, default=-1.0_dp)
      call d%get_real(ic, 41, 50, 'CONTACT/NORMAL', 'M2', v4, ok, default=-1.0_dp)
      call check_tail(d, ic, 51, 'CN, M, CN2, M2 in columns 11-50', ok)
      if (.not. ok) return
      if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
         'CONTACT/NORMAL: CN (columns 11-20) expected a positive roughness constant c_n, found '// &
         rtoa(v1))
      if (.not. (v2 > 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
         'CONTACT/NORMAL: M (columns 21-30) expected a positive exponent m, found '//rtoa(v2))
      if (v3 < 0.0_dp) v3 = 0.5_dp*v1
      if (v4 < 0.0_dp) v4 = v2
      if (.not. (v3 > 0.0_dp)) call d%error_at(ic, 31, 'E-CONTACT', &
         'CONTACT/NORMAL: CN2 (columns 31-40) expected a positive unloading constant, found '// &
         rtoa(v3))
      if (.not. (v4 > 0.0_dp)) call d%error_at(ic, 41, 'E-CONTACT', &
         'CONTACT/NORMAL: M2 (columns 41-50) expected a positive unloading exponent, found '// &
         rtoa(v4))
      if (abs(v4 - v2) <= 1.0e-12_dp*v2 .and. v3 > v1) call d%error_at(ic, 31, 'E-CONTACT', &
         'CONTACT/NORMAL: CN2 = '//rtoa(v3)//' > CN = '//rtoa(v1)//' with M2 = M: the '// &
         'unloading branch would be softer than loading and the residual closure negative '// &
         '(SPEC 2.1)')
      ! M2 < M: u_res = CN p_A^M - CN2 p_A^M2 < 0 for every reversal pressure p_A below
      ! (CN2/CN)^(1/(M - M2)), and every load path passes through small pressures
      if (v4 < v2*(1.0_dp - 1.0e-12_dp) .and. v2 > 0.0_dp .and. v3 > 0.0_dp) call d%error_at(ic, &
         41, 'E-CONTACT', 'CONTACT/NORMAL: M2 (columns 41-50) expected at least M = '//rtoa(v2)// &
         ', found '//rtoa(v4)//': with M2 < M the residual closure CN p_A^M - CN2 p_A^M2 is '// &
         'negative for every reversal pressure p_A below '//rtoa((v3/v1)**(1.0_dp/(v2 - v4)))// &
         ' (in the UNITS of the interface)')
      s%law%cn_in = v1
      s%law%m_in = v2
      s%law%cn2_in = v3
      s%law%m2_in = v4
      s%have_normal = .true.
   end subroutine read_normal

   !> TANGENT: R (11-20) and S (21-30); a blank field keeps the default
   !! (R from eq. 2.8, S = 1 - m).
   subroutine read_tangent(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      real(dp) :: v1, v2
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/TANGENT', 'R', v1, ok, default=-1.0_dp)
      call d%get_real(ic, 21, 30, 'CONTACT/TANGENT', 'S', v2, ok, default=-1.0_dp)
      call check_tail(d, ic, 31, 'R, S in columns 11-30', ok)
      if (.not. ok) return
      if (len_trim(d%field_text(ic, 11, 20)) > 0) then
         if (.not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/TANGENT: R (columns 11-20) expected a positive constant, found '//rtoa(v1))
         law%r_in = v1
         law%r_given = .true.
      end if
      if (len_trim(d%field_text(ic, 21, 30)) > 0) then
         if (v2 < 0.0_dp) call d%error_at(ic, 21, 'E-CONTACT', &
            'CONTACT/TANGENT: S (columns 21-30) expected an exponent >= 0, found '//rtoa(v2))
         law%s_in = v2
         law%s_given = .true.
      end if
   end subroutine read_tangent

   !> FRICTION: NONE; COULOMB MU; or FREDRIKSSON MU_M BETA N (N in 1/length).
   subroutine read_friction(d, ic, s)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(iface_spec_t), intent(inout) :: s
      logical :: ok
      character(len=:), allocatable :: kind
      real(dp) :: mu, beta, rate
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/FRICTION', 'LAW', kind, ok)
      if (.not. ok) return
      ! FREDRIKSSON does not fit ten columns: any abbreviation of 4+ letters
      if (len(kind) >= 4 .and. len(kind) <= 11) then
         if (kind == 'FREDRIKSSON'(1:len(kind))) kind = 'FREDRIKSSON'
      end if
      select case (kind)
      case ('NONE')
         call check_tail(d, ic, 21, 'NONE alone', ok)
         s%law%friction = FRICTION_NONE
         s%law%mu_m = 0.0_dp
      case ('COULOMB')
         call d%get_real(ic, 21, 30, 'CONTACT/FRICTION', 'MU', mu, ok)
         call check_tail(d, ic, 31, 'COULOMB and MU in columns 11-30', ok)
         if (.not. ok) return
         if (.not. (mu >= 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
            'CONTACT/FRICTION: MU (columns 21-30) expected a friction coefficient >= 0, found '// &
            rtoa(mu))
         s%law%friction = FRICTION_COULOMB
         s%law%mu_m = mu
         s%law%beta = 1.0_dp
      case ('FREDRIKSSON')
         call d%get_real(ic, 21, 30, 'CONTACT/FRICTION', 'MU_M', mu, ok)
         call d%get_real(ic, 31, 40, 'CONTACT/FRICTION', 'BETA', beta, ok)
         call d%get_real(ic, 41, 50, 'CONTACT/FRICTION', 'N', rate, ok)
         call check_tail(d, ic, 51, 'FREDRIKSSON, MU_M, BETA, N in columns 11-50', ok)
         if (.not. ok) return
         if (.not. (mu >= 0.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
            'CONTACT/FRICTION: MU_M (columns 21-30) expected a friction coefficient >= 0, '// &
            'found '//rtoa(mu))
         if (.not. (beta > 0.0_dp .and. beta <= 1.0_dp)) call d%error_at(ic, 31, 'E-CONTACT', &
            'CONTACT/FRICTION: BETA (columns 31-40) expected the initial fraction of mu_m in '// &
            '(0, 1], found '//rtoa(beta))
         if (.not. (rate >= 0.0_dp)) call d%error_at(ic, 41, 'E-CONTACT', &
            'CONTACT/FRICTION: N (columns 41-50) expected a hardening rate >= 0 (1/length), '// &
            'found '//rtoa(rate))
         s%law%friction = FRICTION_FREDRIKSSON
         s%law%mu_m = mu
         s%law%beta = beta
         s%law%n_hard = rate
      case default
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/FRICTION (columns 11-20) expected NONE, COULOMB or FREDRIKSSON, found "'// &
            kind//'"')
         return
      end select
      s%have_friction = .true.
   end subroutine read_friction

   !> HARDENING: ON or OFF (11-20) and KAPPA = k_T^p / k_T^e (21-30).
   subroutine read_hardening(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/HARDENING', 'ON/OFF', w, ok)
      call d%get_real(ic, 21, 30, 'CONTACT/HARDENING', 'KAPPA', v1, ok, default=0.045_dp)
      call check_tail(d, ic, 31, 'ON or OFF and KAPPA in columns 11-30', ok)
      if (.not. ok) return
      if (w == 'ON') then
         law%hardening = .true.
      else if (w == 'OFF') then
         law%hardening = .false.
      else
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/HARDENING (columns 11-20) expected ON or OFF, found "'//w//'"')
      end if
      if (.not. (v1 > 0.0_dp .and. v1 <= 1.0_dp)) call d%error_at(ic, 21, 'E-CONTACT', &
         'CONTACT/HARDENING: KAPPA (columns 21-30) expected a ratio k_T^p/k_T^e in (0, 1], '// &
         'found '//rtoa(v1))
      law%kappa = v1
   end subroutine read_hardening

   !> SLIP: IRREVERSIBLE or GROSS (11-20), what the effective slip v_e counts.
   subroutine read_slip(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      character(len=:), allocatable :: w
      logical :: ok
      ok = .true.
      call d%get_word(ic, 11, 20, 'CONTACT/SLIP', 'DEFINITION', w, ok)
      if (w == 'IRREVERSIBLE') then
         law%slip_def = SLIP_IRREVERSIBLE
      else if (w == 'GROSS') then
         law%slip_def = SLIP_GROSS
      else if (ok) then
         call d%error_at(ic, 11, 'E-CONTACT', &
            'CONTACT/SLIP (columns 11-20) expected IRREVERSIBLE or GROSS, found "'//w//'"')
      end if
   end subroutine read_slip

   !> TOLERANCE: the pairing tolerance TOL (11-20) [model length].
   subroutine read_tolerance(d, ic, law)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      type(interface_t), intent(inout) :: law
      real(dp) :: v1
      logical :: ok
      ok = .true.
      call d%get_real(ic, 11, 20, 'CONTACT/TOLERANCE', 'TOL', v1, ok)
      call check_tail(d, ic, 21, 'TOL in columns 11-20', ok)
      if (ok .and. .not. (v1 > 0.0_dp)) call d%error_at(ic, 11, 'E-CONTACT', &
         'CONTACT/TOLERANCE (columns 11-20) expected a positive distance, found '//rtoa(v1))
      if (ok) law%tol = v1
   end subroutine read_tolerance
end module deck_contact_law
