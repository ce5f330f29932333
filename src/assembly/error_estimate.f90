!> A posteriori error estimate of a step: the recovery-based (Zienkiewicz-Zhu)
!! estimate of the bodies' discretization error in the energy norm, element
!! by element, and an indicator of how well the contact pairs resolve the
!! contact pressure.
!!
!! Bodies.  The recovered stresses sigma* come from superconvergent patch
!! recovery: around every corner node of the mesh, the elements that share
!! it (the node's patch; elements of another material form a patch of their
!! own, since the stresses jump there) fit one polynomial to their sampled
!! stresses (kernels in `error_estimator`): the Gauss-point stresses of T3
!! and Q4, and for Q8 and Q9 the stresses at their 2 x 2 Gauss points, the
!! superconvergent points of the quadratic elements (ZZ Part 1; sampled at
!! the 3 x 3 points of their stiffness rule, the error of Lame's cylinder is
!! underestimated by 15 - 30 %).  Every patch gives its polynomial's value at
!! all nodes of its elements, and the values a node receives (one from each
!! patch that holds it) are averaged (per material).  Interior patches come
!! first: a patch on the boundary fits from one side and, on a curved
!! boundary, from points near one line.  A node that no interior patch
!! reaches takes the patches around it, boundary ones too, with the
!! element's polynomial or, where their points do not determine it (a corner
!! patch of one T3, a strip one element thick), the linear and then the
!! constant one.  sigma* is interpolated in each element by its
!! shape functions, and
!!
!!     ||e*||_E,e^2 = int_e (sigma* - sigma_h)^T D^-1 (sigma* - sigma_h) dV,
!!     eta_e = ||e*||_E,e / sqrt(||u_h||_E^2 + ||e*||_E^2),
!!     eta   = ||e*||_E / sqrt(||u_h||_E^2 + ||e*||_E^2) = sqrt(sum_e eta_e^2),
!!
!! with the norms of the whole model in the denominators (error_indicator
!! and estimated_error of the body fields record).  The field is exact where
!! the FE stresses are a polynomial of the recovery's degree, so a patch test
!! gives zero.
!!
!! Interface.  The pairs of every interface are ordered along it (by their
!! position projected on the interface's mean tangent); a pair's resolution
!! indicator is the larger jump of the contact pressure to its two
!! neighbours, relative to the interface's peak pressure: ~ |dp/ds| s / p_max
!! for a pair spacing s, and at the edge of the contact zone the pressure
!! of the last closed pair (the edge lies inside one spacing).  The contact
!! zone of an interface is the range of its closed pairs; its width (2a; a in a half model) runs
!! to the midpoints between the outermost closed pairs and their open
!! neighbours (to the outermost pair itself where the zone reaches the end of
!! the interface).
!!
!! Ref: Zienkiewicz & Zhu, IJNME 33 (1992) 1331-1364 (Part 1, the recovery)
!!      and 1365-1382 (Part 2, error estimates).
module error_estimate
   use kinds, only: dp
   use errors, only: status_t, STAT_JACOBIAN
   use strings, only: itoa
   use model, only: model_t, MAX_NODE
   use records, only: body_fields_t, contact_fields_t, NS_OPEN
   use topology, only: corner_count
   use error_estimator, only: MAX_TERMS, recovery_terms, patch_fit, fit_basis_xy, &
                              element_error_energy, rule_shapes, point_stresses
   use quadrature, only: max_gp
   implicit none
   private
   public :: estimate_error, recover_patch_stresses, interface_resolution

   !> Shape functions, natural derivatives and weights of one Gauss rule of
   !! one element type (the same for every element of the type).
   type :: rule_t
      integer :: ngp = 0
      real(dp), allocatable :: shp(:, :)       !! (nnode, ngp)
      real(dp), allocatable :: der(:, :, :)    !! (2, nnode, ngp)
      real(dp), allocatable :: w(:)            !! (ngp)
   end type rule_t

contains

   !> The error estimate of the step whose stresses the body fields hold
   !! (error_indicator, estimated_error, error_norm, energy_norm), and the
   !! interface's resolution indicators in the contact fields (if it has pairs).
   subroutine estimate_error(m, body, cf, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(inout) :: body
      type(contact_fields_t), intent(inout) :: cf
      type(status_t), intent(inout) :: status
      real(dp), allocatable :: sstar(:, :, :), e2(:), u2(:)
      real(dp) :: elcod(2, MAX_NODE), total
      type(rule_t) :: rules(MAX_NODE)
      integer :: ie, nn, imat, ierr, k

      call recover_patch_stresses(m, body, sstar, status)
      if (.not. status%ok()) return
      call element_rules(m, m%ngaus, rules)
      allocate (e2(m%nelem), u2(m%nelem))
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         do k = 1, nn
            elcod(:, k) = m%coord(:, m%lnods(k, ie))
         end do
         ierr = -1
         if (rules(nn)%ngp == body%gp_start(ie + 1) - body%gp_start(ie)) then
            call element_error_energy(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                                      m%mats(imat)%poiss, m%mats(imat)%thick, rules(nn)%ngp, &
                                      rules(nn)%shp, rules(nn)%der, rules(nn)%w, &
                                      sstar(:, 1:nn, ie), &
                                      body%sig_gp(:, body%gp_start(ie):body%gp_start(ie + 1) - 1), &
                                      e2(ie), u2(ie), ierr)
         end if
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)// &
                            ' (error estimate): no valid Gauss rule or det J <= 0')
            return
         end if
      end do
      if (allocated(body%error_indicator)) then
         if (size(body%error_indicator) /= m%nelem) deallocate (body%error_indicator)
      end if
      if (.not. allocated(body%error_indicator)) allocate (body%error_indicator(m%nelem))
      total = sum(u2) + sum(e2)
      if (total > 0.0_dp) then
         body%error_indicator = sqrt(e2/total)
         body%estimated_error = sqrt(sum(e2)/total)
      else
         body%error_indicator = 0.0_dp
         body%estimated_error = 0.0_dp
      end if
      body%error_norm = sqrt(sum(e2))
      body%energy_norm = sqrt(sum(u2))
      body%estimated = .true.
      if (allocated(m%contact%pairs) .and. allocated(cf%pressure)) then
         if (size(m%contact%pairs) > 0 .and. size(cf%pressure) == size(m%contact%pairs)) then
            call interface_resolution(m, cf)
         end if
      end if
   end subroutine estimate_error

   !> Recovered stresses sigma* at the nodes of every element, (4, nnode of
   !! the largest element, nelem), by superconvergent patch recovery from the Gauss-point stresses
   !! of the body fields (see the module header).
   subroutine recover_patch_stresses(m, body, sstar, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      real(dp), allocatable, intent(out) :: sstar(:, :, :)
      type(status_t), intent(inout) :: status
      integer, allocatable :: sstart(:)
      real(dp), allocatable :: sxy(:, :), ssig(:, :)
      integer :: ie

      ! the Gauss-point stresses of the body fields themselves where every element samples them
      ! (T3, Q4, Q8/Q9 on 2 x 2 points): no copy
      do ie = 1, m%nelem
         if (m%nnode_e(ie) >= 8 .and. body%gp_start(ie + 1) - body%gp_start(ie) /= 4) exit
      end do
      if (ie > m%nelem) then
         call recover_from_samples(m, body, body%gp_start, body%xygp, body%sig_gp, sstar)
         return
      end if
      call sample_stresses(m, body, sstart, sxy, ssig, status)
      if (.not. status%ok()) return
      call recover_from_samples(m, body, sstart, sxy, ssig, sstar)
   end subroutine recover_patch_stresses

   !> recover_patch_stresses from the samples sxy, ssig (sstart: the first of each element).
   subroutine recover_from_samples(m, body, sstart, sxy, ssig, sstar)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      integer, contiguous, intent(in) :: sstart(:)
      real(dp), contiguous, intent(in) :: sxy(:, :), ssig(:, :)
      real(dp), allocatable, intent(out) :: sstar(:, :, :)
      integer, allocatable :: slot(:, :), pstart(:), pelem(:)
      real(dp), allocatable :: acc(:, :), acc2(:, :), wxy(:, :), wsg(:, :)
      integer, allocatable :: cnt(:), cnt2(:), seen(:), wel(:), wnc(:), wcorn(:, :)
      integer :: ie, k, ip, nslot, pass, maxpt, maxnn, npatch, maxpel

      maxnn = 1
      if (m%nelem > 0) maxnn = maxval(m%nnode_e(1:m%nelem))
      call value_slots(m, maxnn, slot, nslot)
      call corner_patches(m, pstart, pelem)
      ! work arrays for the largest patch
      maxpt = 1
      do ip = 1, m%npoin
         k = 0
         do ie = pstart(ip), pstart(ip + 1) - 1
            k = k + sstart(pelem(ie) + 1) - sstart(pelem(ie))
         end do
         maxpt = max(maxpt, k)
      end do
      allocate (wxy(2, maxpt), wsg(4, maxpt))
      allocate (acc(4, nslot), cnt(nslot), acc2(4, nslot), cnt2(nslot), seen(nslot))
      seen = 0
      npatch = 0
      acc = 0.0_dp
      cnt = 0
      acc2 = 0.0_dp
      cnt2 = 0
      ! pass 1: the interior patches with the elements' polynomial; pass 2: the
      ! slots no interior patch reached, from the patches around them (boundary
      ! ones too), with the elements' polynomial or, failing that, a smaller one
      maxpel = 1
      do ip = 1, m%npoin
         maxpel = max(maxpel, pstart(ip + 1) - pstart(ip))
      end do
      allocate (wel(maxpel), wnc(maxpel), wcorn(4, maxpel))
      do pass = 1, 2
         if (pass == 2) then
            if (all(cnt > 0)) exit      ! every slot reached by an interior patch
         end if
         do ip = 1, m%npoin
            if (pstart(ip + 1) == pstart(ip)) cycle
            call fit_node_patch(ip, pelem(pstart(ip):pstart(ip + 1) - 1), pass)
         end do
      end do
      ! (4, nnode, nelem) with nnode the largest element's: entries beyond an element's nodes unused
      allocate (sstar(4, maxnn, m%nelem))
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            if (cnt(slot(k, ie)) > 0) then
               sstar(:, k, ie) = acc(:, slot(k, ie))/cnt(slot(k, ie))
            else if (cnt2(slot(k, ie)) > 0) then
               sstar(:, k, ie) = acc2(:, slot(k, ie))/cnt2(slot(k, ie))
            else
               sstar(:, k, ie) = body%sig_nd(:, m%lnods(k, ie))
            end if
         end do
      end do

   contains

      !> Fit the patch of corner node ip (its elements pel), one material at a
      !! time, and add the values at the elements' nodes.  Pass 1 fits only
      !! interior patches (both corner edges at ip of every element shared
      !! with another element of the material in the patch): a boundary patch
      !! fits from one side and, on a curved boundary, from points near one
      !! line, where its polynomial is nearly undetermined.
      subroutine fit_node_patch(ip, pel, pass)
         integer, intent(in) :: ip, pel(:), pass
         real(dp) :: coef(MAX_TERMS, 4), h, centre(2)
         integer :: imat, j, ie, k, n, npt, g0, nterm, t, tries(3), nsel, l, side, other
         logical :: ok, need, shared
         centre = m%coord(:, ip)
         do j = 1, size(pel)
            imat = m%matno(pel(j))
            ! each material once: at its first element in the patch
            if (j > 1) then
               if (any(m%matno(pel(1:j - 1)) == imat)) cycle
            end if
            ! the elements of the material and their corners
            nsel = 0
            do k = j, size(pel)
               ie = pel(k)
               if (m%matno(ie) /= imat) cycle
               nsel = nsel + 1
               wel(nsel) = ie
               wnc(nsel) = corner_count(m%nnode_e(ie))
               wcorn(1:wnc(nsel), nsel) = m%lnods(1:wnc(nsel), ie)
            end do
            if (pass == 2) then
               need = .false.
               do k = 1, nsel
                  ie = wel(k)
                  if (any(cnt(slot(1:m%nnode_e(ie), ie)) == 0)) need = .true.
               end do
               if (.not. need) cycle
            else
               ! interior: both neighbours of ip along the corners of every element are corners
               ! of another element of the selection
               shared = .true.
               elements: do k = 1, nsel
                  n = findloc(wcorn(1:wnc(k), k), ip, 1)
                  do side = -1, 1, 2
                     l = n + side                          ! the neighbouring corner, cyclic
                     if (l < 1) l = wnc(k)
                     if (l > wnc(k)) l = 1
                     other = wcorn(l, k)
                     shared = .false.
                     others: do l = 1, nsel
                        if (l == k) cycle others
                        do g0 = 1, wnc(l)
                           if (wcorn(g0, l) == other) then
                              shared = .true.
                              exit others
                           end if
                        end do
                     end do others
                     if (.not. shared) exit elements
                  end do
               end do elements
               if (.not. shared) cycle
            end if
            npt = 0
            h = 0.0_dp
            nterm = MAX_TERMS
            do k = 1, nsel
               ie = wel(k)
               nterm = min(nterm, recovery_terms(m%nnode_e(ie)))
               do n = 1, m%nnode_e(ie)
                  l = m%lnods(n, ie)
                  h = max(h, abs(m%coord(1, l) - centre(1)), abs(m%coord(2, l) - centre(2)))
               end do
               do g0 = sstart(ie), sstart(ie + 1) - 1
                  npt = npt + 1
                  wxy(1, npt) = sxy(1, g0)
                  wxy(2, npt) = sxy(2, g0)
                  wsg(1, npt) = ssig(1, g0)
                  wsg(2, npt) = ssig(2, g0)
                  wsg(3, npt) = ssig(3, g0)
                  wsg(4, npt) = ssig(4, g0)
               end do
            end do
            tries = [nterm, 3, 1]
            ok = .false.
            do t = 1, merge(1, 3, pass == 1)
               if (t > 1 .and. tries(t) >= nterm) cycle
               call patch_fit(tries(t), npt, wxy(:, 1:npt), wsg(:, 1:npt), centre, h, coef, ok)
               if (ok) exit
            end do
            if (.not. ok) cycle
            npatch = npatch + 1
            do k = 1, nsel
               call add_values(wel(k), tries(t), coef, centre, h, pass)
            end do
         end do
      end subroutine fit_node_patch

      !> The patch's values at the nodes of element ie, each node once per
      !! patch (npatch numbers the fitted patches).
      subroutine add_values(ie, nterm, coef, centre, h, pass)
         integer, intent(in) :: ie, nterm, pass
         real(dp), intent(in) :: coef(MAX_TERMS, 4), centre(2), h
         real(dp) :: phi(MAX_TERMS), v(4), x, y
         integer :: k, is, l
         do k = 1, m%nnode_e(ie)
            is = slot(k, ie)
            if (seen(is) == npatch) cycle
            seen(is) = npatch
            if (pass == 2 .and. cnt(is) /= 0) cycle
            ! the value there: patch_value's sum, inline
            x = (m%coord(1, m%lnods(k, ie)) - centre(1))/h
            y = (m%coord(2, m%lnods(k, ie)) - centre(2))/h
            if (nterm == 4) then
               v = coef(1, :) + x*coef(2, :) + y*coef(3, :) + (x*y)*coef(4, :)
            else
               call fit_basis_xy(nterm, x, y, phi)
               v = phi(1)*coef(1, :)
               do l = 2, nterm
                  v = v + phi(l)*coef(l, :)
               end do
            end if
            if (pass == 1) then
               acc(:, is) = acc(:, is) + v
               cnt(is) = cnt(is) + 1
            else
               acc2(:, is) = acc2(:, is) + v
               cnt2(is) = cnt2(is) + 1
            end if
         end do
      end subroutine add_values
   end subroutine recover_from_samples

   !> One recovered value per (node, material): the slot of every element
   !! node (slot(k, ie) for node k of element ie; nslot slots in all).
   subroutine value_slots(m, maxnn, slot, nslot)
      type(model_t), intent(in) :: m
      integer, intent(in) :: maxnn                         !! nodes of the largest element
      integer, allocatable, intent(out) :: slot(:, :)      !! (maxnn, nelem)
      integer, intent(out) :: nslot
      integer, allocatable :: matslot(:, :)
      integer :: nmat, ie, k, ip
      nmat = max(1, m%nmats)
      if (m%nelem > 0) nmat = max(nmat, maxval(m%matno))
      allocate (matslot(nmat, m%npoin), slot(maxnn, m%nelem))
      matslot = 0
      slot = 0
      nslot = 0
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            ip = m%lnods(k, ie)
            if (matslot(m%matno(ie), ip) == 0) then
               nslot = nslot + 1
               matslot(m%matno(ie), ip) = nslot
            end if
            slot(k, ie) = matslot(m%matno(ie), ip)
         end do
      end do
   end subroutine value_slots

   !> The patches: the elements around every corner node, in CSR form
   !! (elements pelem(pstart(ip) : pstart(ip + 1) - 1) hold node ip as a corner).
   subroutine corner_patches(m, pstart, pelem)
      type(model_t), intent(in) :: m
      integer, allocatable, intent(out) :: pstart(:), pelem(:)
      integer, allocatable :: cnt(:)
      integer :: ie, k, ip
      allocate (pstart(m%npoin + 1))
      pstart = 0
      do ie = 1, m%nelem
         do k = 1, corner_count(m%nnode_e(ie))
            pstart(m%lnods(k, ie) + 1) = pstart(m%lnods(k, ie) + 1) + 1
         end do
      end do
      pstart(1) = 1
      do ip = 1, m%npoin
         pstart(ip + 1) = pstart(ip + 1) + pstart(ip)
      end do
      allocate (pelem(pstart(m%npoin + 1) - 1), cnt(m%npoin))
      cnt = 0
      do ie = 1, m%nelem
         do k = 1, corner_count(m%nnode_e(ie))
            ip = m%lnods(k, ie)
            pelem(pstart(ip) + cnt(ip)) = ie
            cnt(ip) = cnt(ip) + 1
         end do
      end do
      deallocate (cnt)
   end subroutine corner_patches

   !> The stresses the patches fit, element by element (sstart: first sample
   !! of each element): the Gauss-point stresses of the body fields, except
   !! for Q8 and Q9 with a rule other than 2 x 2, which are sampled at their
   !! 2 x 2 Gauss points from the displacements.
   subroutine sample_stresses(m, body, sstart, sxy, ssig, status)
      type(model_t), intent(in) :: m
      type(body_fields_t), intent(in) :: body
      integer, allocatable, intent(out) :: sstart(:)
      real(dp), allocatable, intent(out) :: sxy(:, :), ssig(:, :)
      type(status_t), intent(inout) :: status
      type(rule_t) :: r2(MAX_NODE)
      real(dp) :: elcod(2, MAX_NODE), eldis(2, MAX_NODE)
      integer :: ie, nn, ngp, ierr, imat, k
      logical, allocatable :: own(:)
      allocate (sstart(m%nelem + 1), own(m%nelem))
      sstart(1) = 1
      do ie = 1, m%nelem
         ngp = body%gp_start(ie + 1) - body%gp_start(ie)
         own(ie) = m%nnode_e(ie) < 8 .or. ngp == 4
         sstart(ie + 1) = sstart(ie) + merge(ngp, 4, own(ie))
      end do
      allocate (sxy(2, sstart(m%nelem + 1) - 1), ssig(4, sstart(m%nelem + 1) - 1))
      if (.not. all(own)) call element_rules(m, 2, r2)
      do ie = 1, m%nelem
         if (own(ie)) then
            associate (g0 => body%gp_start(ie), g1 => body%gp_start(ie + 1) - 1)
               sxy(:, sstart(ie):sstart(ie + 1) - 1) = body%xygp(:, g0:g1)
               ssig(:, sstart(ie):sstart(ie + 1) - 1) = body%sig_gp(:, g0:g1)
            end associate
            cycle
         end if
         nn = m%nnode_e(ie)
         imat = m%matno(ie)
         do k = 1, nn
            elcod(:, k) = m%coord(:, m%lnods(k, ie))
            eldis(:, k) = body%disp(:, m%lnods(k, ie))
         end do
         ierr = -1
         if (r2(nn)%ngp == 4) then
            call point_stresses(m%ntype, nn, elcod(:, 1:nn), m%mats(imat)%young, &
                                m%mats(imat)%poiss, eldis(:, 1:nn), 4, r2(nn)%shp, r2(nn)%der, &
                                sxy(:, sstart(ie):sstart(ie) + 3), &
                                ssig(:, sstart(ie):sstart(ie) + 3), ierr)
         end if
         if (ierr /= 0) then
            call status%set(STAT_JACOBIAN, 'element '//itoa(ie)// &
                            ' (error estimate): its 2 x 2 Gauss points fail')
            return
         end if
      end do
   end subroutine sample_stresses

   !> The Gauss rule `ngaus` of every element type of the model.
   subroutine element_rules(m, ngaus, rules)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ngaus
      type(rule_t), intent(out) :: rules(MAX_NODE)
      real(dp) :: shp(MAX_NODE, max_gp), der(2, MAX_NODE, max_gp), w(max_gp)
      integer :: nn, ngp
      do nn = 1, MAX_NODE
         if (recovery_terms(nn) == 0) cycle
         if (.not. any(m%nnode_e(1:m%nelem) == nn)) cycle
         call rule_shapes(nn, m%ntype, ngaus, ngp, shp(1:nn, :), der(:, 1:nn, :), w)
         rules(nn)%ngp = ngp
         ! (allocated here, not on assignment: the compiler's reallocation reads the bounds of
         ! the unallocated components, garbage that a checked build traps as an overflow)
         allocate (rules(nn)%shp(nn, ngp), rules(nn)%der(2, nn, ngp), rules(nn)%w(ngp))
         rules(nn)%shp = shp(1:nn, 1:ngp)
         rules(nn)%der = der(:, 1:nn, 1:ngp)
         rules(nn)%w = w(1:ngp)
      end do
   end subroutine element_rules

   !> Resolution indicators of the contact pressure (see the module header):
   !! cf%resolution per pair, cf%zone_width, zone_pairs and zone_jump per
   !! interface.
   subroutine interface_resolution(m, cf)
      type(model_t), intent(in) :: m
      type(contact_fields_t), intent(inout) :: cf
      integer :: nif, jf, np, j, k, n, first, last
      integer, allocatable :: idx(:)
      real(dp), allocatable :: s(:)
      real(dp) :: tmean(2), pmax, lo, hi
      logical :: closed_j

      associate (pairs => m%contact%pairs)
         np = size(pairs)
         nif = max(1, maxval(pairs%iface))
         if (allocated(cf%resolution)) then
            deallocate (cf%resolution, cf%zone_width, cf%zone_pairs, cf%zone_jump)
         end if
         allocate (cf%resolution(np), cf%zone_width(nif), cf%zone_pairs(nif), cf%zone_jump(nif))
         cf%resolution = 0.0_dp
         cf%zone_width = 0.0_dp
         cf%zone_pairs = 0
         cf%zone_jump = 0.0_dp
         do jf = 1, nif
            idx = pack([(j, j=1, np)], pairs%iface == jf)
            n = size(idx)
            if (n == 0) cycle
            tmean = 0.0_dp
            do k = 1, n
               ! tangents of one orientation (a curved interface turns less than 180 degrees)
               tmean = tmean + sign(1.0_dp, dot_product(pairs(idx(k))%t, pairs(idx(1))%t)) &
                       *pairs(idx(k))%t
            end do
            if (norm2(tmean) > 0.0_dp) tmean = tmean/norm2(tmean)
            s = [(dot_product(pairs(idx(k))%position, tmean), k=1, n)]
            call sort_by_key(s, idx)
            pmax = maxval(cf%pressure(idx))
            first = 0
            last = 0
            do k = 1, n
               j = idx(k)
               closed_j = cf%normal_state(j) /= NS_OPEN
               if (closed_j) then
                  if (first == 0) first = k
                  last = k
                  cf%zone_pairs(jf) = cf%zone_pairs(jf) + 1
               end if
               if (pmax <= 0.0_dp) cycle
               if (k > 1) cf%resolution(j) = max(cf%resolution(j), &
                                                 abs(cf%pressure(j) - cf%pressure(idx(k - 1)))/pmax)
               if (k < n) cf%resolution(j) = max(cf%resolution(j), &
                                                 abs(cf%pressure(idx(k + 1)) - cf%pressure(j))/pmax)
            end do
            if (first > 0) then
               lo = s(first)
               hi = s(last)
               if (first > 1) lo = 0.5_dp*(s(first) + s(first - 1))
               if (last < n) hi = 0.5_dp*(s(last) + s(last + 1))
               cf%zone_width(jf) = hi - lo
            end if
            cf%zone_jump(jf) = maxval(cf%resolution(idx))
         end do
      end associate
   end subroutine interface_resolution

   !> Sort the keys s ascending, carrying idx along (merge sort, stable).
   pure subroutine sort_by_key(s, idx)
      real(dp), intent(inout) :: s(:)
      integer, intent(inout) :: idx(:)
      real(dp) :: sw(size(s))
      integer :: iw(size(s)), width, lo, mid, hi, i, j, k, n
      n = size(s)
      width = 1
      do while (width < n)
         do lo = 1, n, 2*width
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo
            j = mid + 1
            do k = lo, hi
               if (i <= mid .and. (j > hi .or. s(min(i, n)) <= s(min(j, n)))) then
                  sw(k) = s(i)
                  iw(k) = idx(i)
                  i = i + 1
               else
                  sw(k) = s(j)
                  iw(k) = idx(j)
                  j = j + 1
               end if
            end do
         end do
         s = sw
         idx = iw
         width = 2*width
      end do
   end subroutine sort_by_key

end module error_estimate
