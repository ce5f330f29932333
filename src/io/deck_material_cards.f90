!> The MATERIALS block of an input deck.
!!
!! Owns the material cards (Young's modulus, Poisson's ratio, thickness)
!! and the check that their elastic constants stay representable through the
!! analysis (`stiffness_fits`).  Errors with file, line and column; the
!! thickness ignored in axisymmetry is a warning (docs/deck-format.md).
module deck_material_cards
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t
   use model, only: model_t, material_t, NTYPE_AXISYMMETRIC
   use deck_blocks, only: next_data_card, report_missing, check_tail
   implicit none
   private

   public :: read_materials, stiffness_fits

contains

   ! ------------------------------------------------------------------ MATERIALS

   subroutine read_materials(d, ickw, m, warnings)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: warnings
      integer :: ic, ncards, imat
      integer, allocatable :: line_of(:)
      real(dp) :: e, nu, t
      logical :: ok

      if (allocated(m%mats)) deallocate (m%mats)
      allocate (m%mats(m%nmats), line_of(m%nmats))
      line_of = 0
      ncards = 0
      do
         ic = next_data_card(d, 'MATERIALS', 'a material card (material number in columns 1-5)')
         if (ic == 0) exit
         ncards = ncards + 1
         ok = .true.
         call d%get_int(ic, 1, 5, 'MATERIALS', 'MATNO', imat, ok)
         call d%get_real(ic, 6, 15, 'MATERIALS', 'E', e, ok)
         call d%get_real(ic, 16, 25, 'MATERIALS', 'NU', nu, ok)
         call d%get_real(ic, 26, 35, 'MATERIALS', 'THICK', t, ok, default=1.0_dp)
         call check_tail(d, ic, 36, 'MATERIALS', 'MATNO, E, NU, THICK in columns 1-35', ok)
         if (.not. ok) cycle
         if (imat < 1 .or. imat > m%nmats) then
            call d%error_at(ic, 1, 'E-RANGE', 'MATERIALS: MATNO (columns 1-5) expected 1..'// &
                            itoa(m%nmats)//' (NMATS), found '//itoa(imat))
            cycle
         end if
         if (line_of(imat) /= 0) then
            call d%error_at(ic, 1, 'E-DUPLICATE', 'MATERIALS: material '//itoa(imat)// &
                            ' is defined twice (first on line '//itoa(line_of(imat))//')')
            cycle
         end if
         line_of(imat) = d%cards(ic)%line
         if (.not. (e > 0.0_dp)) call d%error_at(ic, 6, 'E-MATERIAL', &
                                                 'MATERIALS: E (columns 6-15) expected a '// &
                                                 'positive Young''s modulus, found '//rtoa(e))
         if (.not. (nu > -1.0_dp .and. nu < 0.5_dp)) call d%error_at(ic, 16, 'E-MATERIAL', &
               'MATERIALS: NU (columns 16-25) expected Poisson''s ratio in (-1, 0.5), found '// &
               rtoa(nu))
         if (.not. (t > 0.0_dp)) call d%error_at(ic, 26, 'E-MATERIAL', &
                                                 'MATERIALS: THICK (columns 26-35) expected a '// &
                                                 'positive thickness, found '//rtoa(t))
         if (m%ntype == NTYPE_AXISYMMETRIC .and. len_trim(d%field_text(ic, 26, 35)) > 0 .and. &
             abs(t - 1.0_dp) > 0.0_dp) then
            call warnings%add('W-THICK', 'MATERIALS: THICK is ignored in axisymmetric analysis '// &
                              '(the ring weight 2*pi*r is used)', file=d%file, &
                              line=d%cards(ic)%line, col=26)
         end if
         if (e > 0.0_dp .and. nu > -1.0_dp .and. nu < 0.5_dp .and. t > 0.0_dp) then
            if (.not. stiffness_fits(e, nu, t)) call d%error_at(ic, 6, 'E-MATERIAL', &
                  'MATERIALS: E = '//rtoa(e)//', NU = '//rtoa(nu)//' and THICK = '//rtoa(t)// &
                  ' give elastic constants beyond '//rtoa(sqrt(huge(1.0_dp)))//' or below '// &
                  rtoa(1.0_dp/sqrt(huge(1.0_dp)))//' (the analysis multiplies loads by '// &
                  'compliances and displacements by stiffnesses): out of range')
         end if
         m%mats(imat) = material_t(young=e, poiss=nu, thick=t, line=d%cards(ic)%line)
      end do
      if (ncards /= m%nmats) then
         call d%error_at(ickw, 1, 'E-COUNT', 'MATERIALS: NMATS = '//itoa(m%nmats)// &
                         ' on the control card, but the block has '//itoa(ncards)//' cards')
      else
         call report_missing(d, ickw, 'MATERIALS', 'material', line_of)
      end if
   end subroutine read_materials

   !> Whether the constants of the elasticity matrix D (MODPS: E/(1-nu^2),
   !! E(1-nu)/((1+nu)(1-2nu)), its nu/(1-nu) multiple, G = E/(2(1+nu))),
   !! times the thickness, stay within [1/sqrt(huge), sqrt(huge)]: the analysis
   !! multiplies displacements by stiffnesses (K u, the Schur complement
   !! K_cb K_bb^-1 K_bc) and loads by compliances (u = K^-1 f), and loads and
   !! prescribed displacements are bounded by sqrt(huge) (check_magnitude), so
   !! that every such product stays representable.  Evaluated on logarithms,
   !! so that the check itself cannot overflow.
   !! Ref: Hinton & Owen, *Finite Element Programming*, routine MODPS.
   pure logical function stiffness_fits(e, nu, t)
      real(dp), intent(in) :: e      !! Young's modulus [stress], > 0
      real(dp), intent(in) :: nu     !! Poisson's ratio, in (-1, 0.5)
      real(dp), intent(in) :: t      !! thickness [length], > 0
      real(dp) :: lmax, lmin
      lmax = log(e) + log(max(t, 1.0_dp)) + max(-log(1.0_dp - nu*nu), &
             log(1.0_dp - nu) - log(1.0_dp + nu) - log(1.0_dp - 2.0_dp*nu), &
             log(max(abs(nu), tiny(1.0_dp))) - log(1.0_dp + nu) - log(1.0_dp - 2.0_dp*nu), &
             -log(2.0_dp*(1.0_dp + nu)))
      ! the diagonal constants are at least G = E/(2(1+nu)) > E/3
      lmin = log(e) + log(min(t, 1.0_dp)) - log(3.0_dp)
      stiffness_fits = lmax < 0.5_dp*log(huge(1.0_dp)) .and. lmin > -0.5_dp*log(huge(1.0_dp))
   end function stiffness_fits

end module deck_material_cards
