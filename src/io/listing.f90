!> Printed listing in the style of Hinton & Owen's OUTPUT routine.
!!
!! Three levels: NONE (no listing file), SHORT (input summary and the results
!! of the last increment), FULL (echo of the whole input and the results of
!! every increment).  The terminal only gets a summary and one progress line
!! per increment (written by the driver).
!!
!! Ref: Hinton & Owen (1977), OUTPUT.
module listing
   use kinds, only: dp, pi
   use strings, only: itoa
   use model, only: model_t, ntype_name
   use contact_types, only: contact_def_t
   use contact_algorithm, only: contact_state_t, TS_STICK, TS_PLASTIC, TS_SLIP
   implicit none
   private
   public :: list_header, list_input, list_displacements, list_stresses, principal_stresses, list_contact

contains

   !> Program banner and the control data.
   subroutine list_header(u, m, version, solver_name, neq, nres)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      character(len=*), intent(in) :: version, solver_name
      integer, intent(in) :: neq, nres
      write (u, '(a)') repeat('=', 78)
      write (u, '(a)') ' Kontakt2D '//version//' - static 2D contact of rough elastic bodies'
      write (u, '(a)') repeat('=', 78)
      write (u, '(a)') ' Title        : '//m%title
      write (u, '(a)') ' Deck         : '//m%deck_file
      write (u, '(a)') ' Analysis     : '//ntype_name(m%ntype)
      write (u, '(a,i0,a,i0,a,i0)') ' Nodes        : ', m%npoin, '   elements: ', m%nelem, &
         '   materials: ', m%nmats
      write (u, '(a,i0,a,i0,a,i0)') ' Equations    : ', neq, '   restrained dofs: ', nres, &
         '   load cases: ', m%ncase
      write (u, '(a,i0)') ' Increments   : ', m%nincs
      write (u, '(a)') ' Solver       : '//solver_name
   end subroutine list_header

   !> Echo of the input data (FULL listing).
   subroutine list_input(u, m)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer :: ip, ie, k, i
      write (u, '(/a)') ' NODAL COORDINATES'
      write (u, '(a)') '   NODE         X-COORD         Y-COORD'
      do ip = 1, m%npoin
         write (u, '(i7, 2es16.7)') ip, m%coord(:, ip)
      end do
      write (u, '(/a)') ' ELEMENT CONNECTIVITY'
      write (u, '(a)') '   ELEM  MAT  NODES'
      do ie = 1, m%nelem
         write (u, '(i7, i5, 9i7)') ie, m%matno(ie), m%lnods(1:m%nnode_e(ie), ie)
      end do
      write (u, '(/a)') ' MATERIALS'
      write (u, '(a)') '    MAT               E              NU           THICK'
      do k = 1, m%nmats
         write (u, '(i7, 3es16.7)') k, m%mats(k)%young, m%mats(k)%poiss, m%mats(k)%thick
      end do
      write (u, '(/a)') ' RESTRAINTS'
      write (u, '(a)') '   NODE  CODE   PRESCRIBED-U    PRESCRIBED-V  CASE'
      do k = 1, size(m%fixes)
         write (u, '(i7, 3x, 2i1, 2es16.7, i6)') m%fixes(k)%node, merge(1, 0, m%fixes(k)%fixed), &
            m%fixes(k)%value, m%fixes(k)%icase
      end do
      if (size(m%point_loads) > 0) then
         write (u, '(/a)') ' POINT LOADS'
         write (u, '(a)') '   NODE              FX              FY  CASE'
         do k = 1, size(m%point_loads)
            write (u, '(i7, 2es16.7, i6)') m%point_loads(k)%node, m%point_loads(k)%force, m%point_loads(k)%icase
         end do
      end if
      if (size(m%edge_loads) > 0) then
         write (u, '(/a)') ' EDGE LOADS (nodes in element order: start, end, mid)'
         do k = 1, size(m%edge_loads)
            associate (e => m%edge_loads(k))
               write (u, '(a,i0,a,3i7,a,i0)') '   element ', e%ielem, '  nodes', e%nodes(1:e%nn), '  case ', e%icase
               write (u, '(a,3es14.5)') '      pressure  ', e%pn(1:e%nn)
               write (u, '(a,3es14.5)') '      tangential', e%pt(1:e%nn)
            end associate
         end do
      end if
      if (size(m%body_loads) > 0) then
         write (u, '(/a)') ' BODY FORCES'
         do k = 1, size(m%body_loads)
            write (u, '(a,i0,a,2es14.5,a,i0)') '   material ', m%body_loads(k)%imat, '  b =', &
               m%body_loads(k)%b, '  case ', m%body_loads(k)%icase
         end do
      end if
      write (u, '(/a)') ' LOAD HISTORY (total factor of each load case after each increment)'
      do i = 1, m%nincs
         write (u, '(i7, 6f12.5)') i, m%lambda(:, i)
      end do
   end subroutine list_input

   !> Displacements and reactions of one increment.
   subroutine list_displacements(u, m, inc, lambda, disp, react, restrained)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer, intent(in) :: inc
      real(dp), intent(in) :: lambda(:)
      real(dp), intent(in) :: disp(:, :), react(:, :)
      logical, intent(in) :: restrained(:, :)   !! (2, npoin)
      integer :: ip
      write (u, '(/a)') repeat('-', 78)
      write (u, '(a,i0,a,6f11.5)') ' INCREMENT ', inc, '   load factor(s):', lambda
      write (u, '(a)') repeat('-', 78)
      write (u, '(/a)') ' DISPLACEMENTS'
      write (u, '(a)') '   NODE          X-DISP          Y-DISP'
      do ip = 1, m%npoin
         write (u, '(i7, 2es16.7)') ip, disp(:, ip)
      end do
      write (u, '(/a)') ' REACTIONS'
      write (u, '(a)') '   NODE         X-FORCE         Y-FORCE'
      do ip = 1, m%npoin
         if (any(restrained(:, ip))) write (u, '(i7, 2es16.7)') ip, react(:, ip)
      end do
      write (u, '(a, 2es16.7)') '  TOTAL', sum(react(1, :)), sum(react(2, :))
   end subroutine list_displacements

   !> Gauss-point stresses with principal values (STRESS of Hinton & Owen).
   subroutine list_stresses(u, m, gp_start, xygp, sig)
      integer, intent(in) :: u
      type(model_t), intent(in) :: m
      integer, intent(in) :: gp_start(:)       !! (nelem+1) first Gauss point of each element
      real(dp), intent(in) :: xygp(:, :)       !! (2, ngp)
      real(dp), intent(in) :: sig(:, :)        !! (4, ngp)
      integer :: ie, ig
      real(dp) :: s1, s2, ang
      write (u, '(/a)') ' STRESSES AT GAUSS POINTS'
      write (u, '(a)') '   ELEM  G.P.     X-COORD     Y-COORD   XX-STRESS   YY-STRESS   XY-STRESS'// &
         '   ZZ-STRESS   MAX P.S.   MIN P.S.  ANGLE'
      do ie = 1, m%nelem
         do ig = gp_start(ie), gp_start(ie + 1) - 1
            call principal_stresses(sig(:, ig), s1, s2, ang)
            write (u, '(i7, i5, 8es12.4, f7.2)') ie, ig - gp_start(ie) + 1, xygp(:, ig), sig(:, ig), s1, s2, ang
         end do
      end do
   end subroutine list_stresses

   !> Contact table of one increment: one line per pair.
   subroutine list_contact(u, c, st, iterations, repeats, residual, drift)
      integer, intent(in) :: u
      type(contact_def_t), intent(in) :: c
      type(contact_state_t), intent(in) :: st
      integer, intent(in) :: iterations, repeats
      real(dp), intent(in) :: residual, drift
      integer :: j
      character(len=5) :: ns, ts
      real(dp) :: pn, pt
      write (u, '(/a)') ' CONTACT PAIRS'
      write (u, '(a,i0,a,i0,a,es10.3,a,es10.3)') '   solutions: ', iterations, '   repeats: ', repeats, &
         '   out-of-balance: ', residual, '   normal-law drift: ', drift
      write (u, '(a)') '   PAIR  NODE-A  NODE-B     X-COORD     Y-COORD        AREA    PRESSURE       SHEAR'// &
         '     CLOSURE        SLIP  SLIP-IRREV    MU  NORM  TANG'
      do j = 1, size(c%pairs)
         associate (p => c%pairs(j), s => st%s(j))
            if (.not. s%closed) then
               ns = 'open'
            else if (s%on_unloading) then
               ns = 'unld'
            else
               ns = 'load'
            end if
            select case (s%tstate)
            case (TS_STICK)
               ts = 'stick'
            case (TS_PLASTIC)
               ts = 'plast'
            case (TS_SLIP)
               ts = 'slip'
            end select
            if (.not. s%closed) ts = '-'
            pn = 0.0_dp
            pt = 0.0_dp
            if (p%area > 0.0_dp) then
               pn = s%fn/p%area
               pt = s%ft/p%area
            end if
            write (u, '(i7, 2i8, 8es12.4, f6.3, 2(1x,a5))') j, p%node_a, p%node_b, p%position, p%area, pn, pt, &
               s%un, s%ut, s%utp, s%mu, ns, ts
         end associate
      end do
      write (u, '(a,es14.6,a,es14.6)') '   sum of normal forces:', sum(st%s%fn), '   of tangential forces:', sum(st%s%ft)
   end subroutine list_contact

   !> In-plane principal stresses and the angle (degrees) of the first from x.
   pure subroutine principal_stresses(sig, s1, s2, angle)
      real(dp), intent(in) :: sig(4)
      real(dp), intent(out) :: s1, s2, angle
      real(dp) :: c, r
      c = 0.5_dp*(sig(1) + sig(2))
      r = sqrt((0.5_dp*(sig(1) - sig(2)))**2 + sig(3)**2)
      s1 = c + r
      s2 = c - r
      if (r > 0.0_dp) then
         angle = 0.5_dp*atan2(2.0_dp*sig(3), sig(1) - sig(2))*180.0_dp/pi
      else
         angle = 0.0_dp
      end if
   end subroutine principal_stresses
end module listing
