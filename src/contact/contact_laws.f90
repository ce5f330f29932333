!> The interface laws of the rough contact layer, as pure functions of state.
!!
!! Normal direction (SPEC §2.1): virgin loading u = cn p^m (eq. 2.1a) with
!! tangent stiffness per unit area k_n = p^(1-m) / (cn m) (corrected eq. 3.27,
!! SPEC D4); unloading from the reversal point A = (u_A, p_A) along
!! u = u_A - cn2 (p_A^m2 - p^m2) (SPEC D8), reloading back along it to A and
!! then on the virgin curve.  The branch is admissible for the reversal
!! pressures of `admissible_reversals` (u_res >= 0, unloading at least as stiff
!! as loading at A); beyond them the residual closure is taken as
!! max(u_res, 0): a reversal whose u_A - cn2 p_A^m2 would be negative unloads
!! along the branch of exponent m2 through A and (0, 0), u = u_A (p/p_A)^m2,
!! i.e. with cn2 replaced by u_A / p_A^m2 (`unloading_constant`).
!! Tangential direction (SPEC §2.2): elastic stiffness k_T^e = p_n^S / R
!! (eq. 2.7).  Friction (SPEC §2.3, D1): mu(v_e) = mu_m [1 - (1 - beta)
!! exp(-n v_e)].  Units: model units, after `convert_interface` (SPEC §2.4).
!!
!! No law knows about matrices; the spring element and the algorithm call these.
module contact_laws
   use kinds, only: dp
   use contact_types, only: interface_t, UNITS_KGF_UM, UNITS_N_UM, &
                            FRICTION_NONE, FRICTION_FREDRIKSSON, KGF_PER_NMM2
   implicit none
   private
   public :: convert_interface, r_literature, virgin_pressure, virgin_closure, virgin_tangent, &
             unloading_pressure, unloading_tangent, residual_closure, normal_pressure, &
             normal_tangent, unloading_constant, admissible_reversals, tangential_stiffness, &
             friction_coefficient, bilinear_return

contains

   !> R of eq. (2.8), R = 2 cn m (1 + nu), in the units of the given cn (Back et al. 1973).
   elemental real(dp) function r_literature(cn, m, nu) result(r)
      real(dp), intent(in) :: cn, m, nu
      r = 2.0_dp*cn*m*(1.0_dp + nu)
   end function r_literature

   !> Model-unit constants of an interface from its input values (SPEC §2.4):
   !!     kgf-µm: cn = 1e-3 cn_in f^m,  R = 1e-3 R_in f^(1-S),  f = 10.19716 kgf/cm² per N/mm²
   !!     N-µm:   cn = 1e-3 cn_in,      R = 1e-3 R_in
   !! `nu(j)` is the Poisson ratio at pair j of the interface, used when R is
   !! computed from eq. (2.8).  Requires a model in mm and N/mm² unless units = MODEL.
   pure subroutine convert_interface(ifc, nu)
      type(interface_t), intent(inout) :: ifc
      real(dp), intent(in) :: nu(:)
      real(dp) :: f, lscale
      real(dp) :: r_in(size(nu))

      if (.not. ifc%s_given) ifc%s_in = 1.0_dp - ifc%m_in
      if (ifc%r_given) then
         r_in = ifc%r_in
      else
         r_in = r_literature(ifc%cn_in, ifc%m_in, nu)
      end if
      select case (ifc%units)
      case (UNITS_KGF_UM)
         f = KGF_PER_NMM2
         lscale = 1.0e-3_dp
      case (UNITS_N_UM)
         f = 1.0_dp
         lscale = 1.0e-3_dp
      case default
         f = 1.0_dp
         lscale = 1.0_dp
      end select
      ifc%m = ifc%m_in
      ifc%m2 = ifc%m2_in
      ifc%s = ifc%s_in
      ifc%cn = lscale*ifc%cn_in*f**ifc%m_in
      ifc%cn2 = lscale*ifc%cn2_in*f**ifc%m2_in
      ifc%r_t = lscale*r_in*f**(1.0_dp - ifc%s_in)
   end subroutine convert_interface

   !> Pressure on the virgin curve at closure u (zero for u <= 0), inverse of (2.1a).
   elemental real(dp) function virgin_pressure(u, cn, m) result(p)
      real(dp), intent(in) :: u, cn, m
      if (u <= 0.0_dp) then
         p = 0.0_dp
      else
         p = (u/cn)**(1.0_dp/m)
      end if
   end function virgin_pressure

   !> Closure on the virgin curve at pressure p, eq. (2.1a).
   elemental real(dp) function virgin_closure(p, cn, m) result(u)
      real(dp), intent(in) :: p, cn, m
      u = cn*max(p, 0.0_dp)**m
   end function virgin_closure

   !> Tangent dp/du of the virgin curve at pressure p, corrected eq. (3.27).
   elemental real(dp) function virgin_tangent(p, cn, m) result(k)
      real(dp), intent(in) :: p, cn, m
      k = max(p, 0.0_dp)**(1.0_dp - m)/(cn*m)
   end function virgin_tangent

   !> The range of reversal pressures p_A for which the unloading branch
   !! u = u_A - cn2 (p_A^m2 - p^m2) from a point A = (cn p_A^m, p_A) of the
   !! virgin curve is admissible (SPEC §2.1): both
   !!     u_res >= 0:        cn2 p_A^m2 <= cn p_A^m
   !!     stiff unloading:   cn2 m2 p_A^(m2-1) <= cn m p_A^(m-1)
   !! hold for p_lo <= p_A <= p_hi.  Each reads q <= p_A^(m-m2) with
   !! q = cn2/cn or cn2 m2/(cn m), so with m2 > m: p_lo = 0,
   !! p_hi = p* = min[(cn/cn2)^(1/(m2-m)), (cn m/(cn2 m2))^(1/(m2-m))];
   !! with m2 < m: p_lo = max[(cn2/cn)^(1/(m-m2)), (cn2 m2/(cn m))^(1/(m-m2))],
   !! p_hi = huge; with m2 = m: every p_A (0, huge) if cn2 <= cn, none
   !! (p_lo = huge, p_hi = 0) otherwise.  In the pressure unit of the constants
   !! (the conversion of SPEC §2.4 moves both sides alike).
   elemental subroutine admissible_reversals(cn, m, cn2, m2, p_lo, p_hi)
      real(dp), intent(in) :: cn, m       !! loading: u = cn p^m
      real(dp), intent(in) :: cn2, m2     !! unloading: u = u_A - cn2 (p_A^m2 - p^m2)
      real(dp), intent(out) :: p_lo       !! smallest admissible reversal pressure
      real(dp), intent(out) :: p_hi       !! largest admissible reversal pressure (huge: no bound)
      real(dp) :: q_res, q_stiff
      q_res = cn2/cn
      q_stiff = (cn2*m2)/(cn*m)
      if (m2 > m) then
         p_lo = 0.0_dp
         p_hi = power_root(1.0_dp/max(q_res, q_stiff), m2 - m)
      else if (m2 < m) then
         p_lo = power_root(max(q_res, q_stiff), m - m2)
         p_hi = huge(1.0_dp)
      else if (q_res <= 1.0_dp) then
         p_lo = 0.0_dp
         p_hi = huge(1.0_dp)
      else
         p_lo = huge(1.0_dp)
         p_hi = 0.0_dp
      end if
   end subroutine admissible_reversals

   !> x^(1/e) for x > 0, e > 0, as huge where it would overflow (an exponent
   !! difference m2 - m of round-off size).
   elemental real(dp) function power_root(x, e) result(r)
      real(dp), intent(in) :: x, e
      real(dp) :: lr
      lr = log(x)/e
      if (lr >= log(huge(1.0_dp))) then
         r = huge(1.0_dp)
      else
         r = exp(lr)
      end if
   end function power_root

   !> The constant of the unloading branch from A = (u_A, p_A): cn2, or
   !! u_A / p_A^m2 where cn2 p_A^m2 > u_A (the residual closure would be
   !! negative and is taken as 0: the branch u = u_A (p/p_A)^m2 through A and
   !! the origin, stiffer than the given one).  cn2 without a reversal point.
   elemental real(dp) function unloading_constant(ua, pa, cn2, m2) result(c)
      real(dp), intent(in) :: ua, pa, cn2, m2
      c = cn2
      if (pa > 0.0_dp .and. ua > 0.0_dp) then
         if (cn2*pa**m2 > ua) c = ua/pa**m2
      end if
   end function unloading_constant

   !> Residual closure after unloading from A to p = 0 (SPEC D8), taken as
   !! max(u_A - cn2 p_A^m2, 0) (see unloading_constant).
   elemental real(dp) function residual_closure(ua, pa, cn2, m2) result(ures)
      real(dp), intent(in) :: ua, pa, cn2, m2
      ures = max(ua - cn2*max(pa, 0.0_dp)**m2, 0.0_dp)
   end function residual_closure

   !> Pressure on the unloading branch through A at closure u (zero below the
   !! residual closure); the branch through the origin where u_res is clamped.
   elemental real(dp) function unloading_pressure(u, ua, pa, cn2, m2) result(p)
      real(dp), intent(in) :: u, ua, pa, cn2, m2
      real(dp) :: q
      if (unloading_constant(ua, pa, cn2, m2) < cn2) then
         ! u_res clamped at 0: p = p_A (u/u_A)^(1/m2), exactly zero at u = 0
         p = 0.0_dp
         if (u > 0.0_dp) p = pa*(u/ua)**(1.0_dp/m2)
         return
      end if
      q = max(pa, 0.0_dp)**m2 - (ua - u)/cn2
      if (q <= 0.0_dp) then
         p = 0.0_dp
      else
         p = q**(1.0_dp/m2)
      end if
   end function unloading_pressure

   !> Tangent dp/du of the unloading branch at pressure p; cn2 is the
   !! branch's constant (unloading_constant of its reversal point).
   elemental real(dp) function unloading_tangent(p, cn2, m2) result(k)
      real(dp), intent(in) :: p, cn2, m2
      k = max(p, 0.0_dp)**(1.0_dp - m2)/(cn2*m2)
   end function unloading_tangent

   !> Pressure of the normal law at closure u: the unloading/reloading branch
   !! through A while u < u_A, the virgin curve otherwise.
   elemental real(dp) function normal_pressure(u, cn, m, cn2, m2, on_unloading, ua, pa) result(p)
      real(dp), intent(in) :: u, cn, m, cn2, m2
      logical, intent(in) :: on_unloading
      real(dp), intent(in) :: ua, pa
      if (on_unloading .and. u < ua) then
         p = unloading_pressure(u, ua, pa, cn2, m2)
      else
         p = virgin_pressure(u, cn, m)
      end if
   end function normal_pressure

   !> Tangent dp/du of the normal law at closure u (see normal_pressure).
   elemental real(dp) function normal_tangent(u, cn, m, cn2, m2, on_unloading, ua, pa) result(k)
      real(dp), intent(in) :: u, cn, m, cn2, m2
      logical, intent(in) :: on_unloading
      real(dp), intent(in) :: ua, pa
      if (on_unloading .and. u < ua) then
         k = unloading_tangent(unloading_pressure(u, ua, pa, cn2, m2), &
                               unloading_constant(ua, pa, cn2, m2), m2)
      else
         k = virgin_tangent(virgin_pressure(u, cn, m), cn, m)
      end if
   end function normal_tangent

   !> Elastic tangential stiffness per unit area, eq. (2.7): k_T^e = p_n^S / R.
   elemental real(dp) function tangential_stiffness(p, s, r) result(k)
      real(dp), intent(in) :: p, s, r
      k = max(p, 0.0_dp)**s/r
   end function tangential_stiffness

   !> Exact integration of the bilinear tangential law with the Coulomb
   !! limit over one increment at fixed normal force (return mapping).  The
   !! law is read as linear kinematic hardening (Masing's rule): the elastic
   !! range is the band |F - X| <= r_y, r_y = 0.625 L, centred on the back
   !! force X, and the force is capped at the limit L = mu F_n (gross slip).
   !! From the force f0 an increment du moves elastically (slope k_e) inside
   !! the band, along the hardening branch (slope kappa k_e) at its edge, which
   !! drags X along, and at +-L in slip, where |X| = L - r_y.  On a virgin
   !! path (X = 0) this is the paper's curve (Bild 2: OA, AB, slip); after a
   !! reversal the elastic range is 2 r_y wide, as Masing's rule and the
   !! Mindlin-Deresiewicz microslip solution give.  X is a force; when L
   !! changes it is clamped to |X| <= L - r_y.  Without the branch r_y = L and
   !! X = 0 (elastic-perfectly plastic Coulomb).
   !! tstate: 0 stick (elastic), 1 hardening branch, 2 slip; the sign of the
   !! branch or slip direction is that of f - x.
   !! Ref: G. Masing, Eigenspannungen und Verfestigung beim Messing (1926);
   !! R. D. Mindlin, H. Deresiewicz, J. Appl. Mech. 20 (1953) 327-344.
   pure subroutine bilinear_return(f0, du, ke, kappa, limit, x0, hardening, f, x, tstate)
      real(dp), intent(in) :: f0      !! force at the start of the increment
      real(dp), intent(in) :: du      !! tangential displacement increment
      real(dp), intent(in) :: ke      !! elastic stiffness
      real(dp), intent(in) :: kappa   !! branch slope / elastic slope
      real(dp), intent(in) :: limit   !! L = mu F_n (>= 0)
      real(dp), intent(in) :: x0      !! back force at the start of the increment
      logical, intent(in) :: hardening
      real(dp), intent(out) :: f      !! force at the end of the increment
      real(dp), intent(out) :: x      !! back force at the end of the increment
      integer, intent(out) :: tstate
      real(dp) :: trial, ry, xcap, dsign
      ry = merge(0.625_dp*limit, limit, hardening)
      xcap = max(limit - ry, 0.0_dp)
      x = min(max(x0, -xcap), xcap)
      trial = f0 + ke*du
      tstate = 0
      f = trial
      if (abs(trial - x) <= ry) return
      dsign = sign(1.0_dp, trial - x)
      if (hardening) then
         f = x + dsign*ry + kappa*(trial - x - dsign*ry)
         tstate = 1
         if (abs(f) <= limit) then
            x = f - dsign*ry
            return
         end if
      end if
      f = dsign*limit
      x = dsign*xcap
      tstate = 2
   end subroutine bilinear_return

   !> Friction coefficient after the effective slip ve (SPEC D1):
   !! Coulomb mu_m; Fredriksson mu_m [1 - (1 - beta) exp(-n ve)]; none 0.
   pure real(dp) function friction_coefficient(ifc, ve) result(mu)
      type(interface_t), intent(in) :: ifc
      real(dp), intent(in) :: ve
      select case (ifc%friction)
      case (FRICTION_NONE)
         mu = 0.0_dp
      case (FRICTION_FREDRIKSSON)
         mu = ifc%mu_m*(1.0_dp - (1.0_dp - ifc%beta)*exp(-ifc%n_hard*max(ve, 0.0_dp)))
      case default
         mu = ifc%mu_m
      end select
   end function friction_coefficient
end module contact_laws
