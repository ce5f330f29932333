!> Contact definition: surfaces, pairs, direction cosines and lumped areas.
!!
!! A contact surface is a set of element edges on the boundary of one body
!! (given as a named edge set, or derived from a list or set of nodes: the
!! boundary edges all of whose nodes are in the list).  Node-to-node pairs are
!! built by matching every node of surface A with the node of surface B that
!! lies on its normal line (tangential offset within a tolerance); the local
!! axes (t, n) of a pair are those of surface B at its node (outward normal of
!! body B, averaged over the adjacent edges), and the initial gap is
!! g0 = (x_a - x_b).n (eq. 3.8).
!!
!! Lumped areas (eqs. 3.22, 3.26, 4.2, appendix A1-A6, SPEC §3.2): row-sum
!! lumping of the edge "mass" matrix,
!!     A_j = sum over edges e of j of  int G_j(xi) w(xi) |J(xi)| dxi,
!! with w = t (plane) or 2 pi r (axisymmetric), the arc-length Jacobian |J| and
!! the edges of surface B whose nodes are all paired (the common contact
!! zone), so that the A_j of a surface sum to its nominal area.
module contact_definition
   use kinds, only: dp, two_pi
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use model, only: model_t, find_edge_set, find_node_set, NTYPE_AXISYMMETRIC
   use contact_types, only: contact_pair_t, interface_t, LAW_ROUGH
   use contact_laws, only: convert_interface
   use restraint_check, only: find_bodies
   use shape_2d, only: element_edge_nodes, nedges, edge_shape
   use quadrature, only: gauss_legendre
   implicit none
   private
   public :: surface_spec_t, iface_spec_t, surface_edges, edge_nodes, surface_normals, match_surfaces, &
             lumped_areas, node_poisson, define_contact

   !> A surface as the deck gives it: a set name, or a list of nodes.
   type :: surface_spec_t
      character(len=:), allocatable :: set_name
      integer, allocatable :: nodes(:)
      integer :: line = 0
      logical :: given = .false.
   end type surface_spec_t

   !> What the deck says about one interface, before the pairs are built.
   type :: iface_spec_t
      type(interface_t) :: law
      type(surface_spec_t) :: surf(2)          !! A, B
      integer, allocatable :: pa(:), pb(:)     !! explicit pairs: nodes
      real(dp), allocatable :: pg0(:), palpha(:), parea(:)
      logical, allocatable :: has_g0(:), has_alpha(:), has_area(:)
      integer, allocatable :: pline(:)
      integer :: npair = 0
      logical :: have_normal = .false., have_friction = .false.
      integer :: line = 0
   end type iface_spec_t

contains

   !> Global nodes of edge iedge of element ie, in (start, end, mid) order.
   pure subroutine edge_nodes(m, ie, iedge, nodes, nn)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ie, iedge
      integer, intent(out) :: nodes(3), nn
      integer :: loc(3)
      call element_edge_nodes(m%nnode_e(ie), iedge, loc, nn)
      nodes = 0
      nodes(1:nn) = m%lnods(loc(1:nn), ie)
   end subroutine edge_nodes

   !> The boundary edges of a surface.  msg is '' on success, else the reason.
   subroutine surface_edges(m, spec, ielem, iedge, msg)
      type(model_t), intent(in) :: m
      type(surface_spec_t), intent(in) :: spec
      integer, allocatable, intent(out) :: ielem(:), iedge(:)
      character(len=:), allocatable, intent(out) :: msg
      integer :: ks
      msg = ''
      if (allocated(spec%set_name)) then
         ks = find_edge_set(m, spec%set_name)
         if (ks > 0) then
            ielem = m%edge_sets(ks)%ielem
            iedge = m%edge_sets(ks)%iedge
            return
         end if
         ks = find_node_set(m, spec%set_name)
         if (ks == 0) then
            msg = 'no node or edge set called "'//spec%set_name//'"'
            allocate (ielem(0), iedge(0))
            return
         end if
         call boundary_edges_of(m, m%node_sets(ks)%nodes, ielem, iedge)
      else
         call boundary_edges_of(m, spec%nodes, ielem, iedge)
      end if
      if (size(ielem) == 0) msg = 'the nodes form no element edge on the boundary of a body'
   end subroutine surface_edges

   !> Boundary edges (edges of exactly one element) all of whose nodes are in `nodes`.
   subroutine boundary_edges_of(m, nodes, ielem, iedge)
      type(model_t), intent(in) :: m
      integer, intent(in) :: nodes(:)
      integer, allocatable, intent(out) :: ielem(:), iedge(:)
      logical, allocatable :: inset(:)
      integer, allocatable :: ce(:), ck(:), key1(:), key2(:), idx(:)
      integer :: ie, k, nn, nd(3), n, i, j
      logical :: shared

      allocate (inset(m%npoin))
      inset = .false.
      do i = 1, size(nodes)
         if (nodes(i) >= 1 .and. nodes(i) <= m%npoin) inset(nodes(i)) = .true.
      end do
      n = 0
      allocate (ce(16), ck(16), key1(16), key2(16))
      do ie = 1, m%nelem
         do k = 1, nedges(m%nnode_e(ie))
            call edge_nodes(m, ie, k, nd, nn)
            if (.not. all(inset(nd(1:nn)))) cycle
            if (n >= size(ce)) then
               ce = [ce, ce]
               ck = [ck, ck]
               key1 = [key1, key1]
               key2 = [key2, key2]
            end if
            n = n + 1
            ce(n) = ie
            ck(n) = k
            key1(n) = min(nd(1), nd(2))
            key2(n) = max(nd(1), nd(2))
         end do
      end do
      ! an edge shared by two elements lies inside the mesh: drop both copies
      allocate (idx(n))
      call sort_pairs(key1(1:n), key2(1:n), idx)
      allocate (ielem(n), iedge(n))
      j = 0
      do i = 1, n
         shared = .false.
         if (i > 1) shared = shared .or. (key1(idx(i)) == key1(idx(i - 1)) .and. key2(idx(i)) == key2(idx(i - 1)))
         if (i < n) shared = shared .or. (key1(idx(i)) == key1(idx(i + 1)) .and. key2(idx(i)) == key2(idx(i + 1)))
         if (shared) cycle
         j = j + 1
         ielem(j) = ce(idx(i))
         iedge(j) = ck(idx(i))
      end do
      ielem = ielem(1:j)
      iedge = iedge(1:j)
   end subroutine boundary_edges_of

   !> Order idx so that (k1, k2)(idx) is lexicographically sorted (merge sort).
   subroutine sort_pairs(k1, k2, idx)
      integer, intent(in) :: k1(:), k2(:)
      integer, intent(out) :: idx(:)
      integer, allocatable :: tmp(:)
      integer :: n, width, lo, mid, hi, i, j, k
      n = size(k1)
      idx = [(i, i=1, n)]
      allocate (tmp(n))
      width = 1
      do while (width < n)
         lo = 1
         do while (lo <= n)
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo
            j = mid + 1
            k = lo
            do while (i <= mid .and. j <= hi)
               if (less(idx(j), idx(i))) then
                  tmp(k) = idx(j)
                  j = j + 1
               else
                  tmp(k) = idx(i)
                  i = i + 1
               end if
               k = k + 1
            end do
            do while (i <= mid)
               tmp(k) = idx(i)
               i = i + 1
               k = k + 1
            end do
            do while (j <= hi)
               tmp(k) = idx(j)
               j = j + 1
               k = k + 1
            end do
            lo = lo + 2*width
         end do
         idx = tmp
         width = 2*width
      end do
   contains
      pure logical function less(a, b)
         integer, intent(in) :: a, b
         less = k1(a) < k1(b) .or. (k1(a) == k1(b) .and. k2(a) < k2(b))
      end function less
   end subroutine sort_pairs

   !> Outward unit normal of body B at every node of its surface edges: the
   !! length-weighted mean of the adjacent edges' normals, each evaluated at
   !! the node (exact for curved quadratic edges).  Nodes off the surface get 0.
   subroutine surface_normals(m, ielem, iedge, normal)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)
      real(dp), intent(out) :: normal(:, :)    !! (2, npoin)
      real(dp), parameter :: snode(3) = [-1.0_dp, 1.0_dp, 0.0_dp]
      real(dp) :: shape(3), deriv(3), dx, dy, len_e, xy(2, 3)
      integer :: k, nd(3), nn, j
      normal = 0.0_dp
      do k = 1, size(ielem)
         call edge_nodes(m, ielem(k), iedge(k), nd, nn)
         xy(:, 1:nn) = m%coord(:, nd(1:nn))
         len_e = norm2(xy(:, 2) - xy(:, 1))
         do j = 1, nn
            call edge_shape(nn, snode(j), shape(1:nn), deriv(1:nn))
            dx = dot_product(deriv(1:nn), xy(1, 1:nn))
            dy = dot_product(deriv(1:nn), xy(2, 1:nn))
            normal(:, nd(j)) = normal(:, nd(j)) + len_e*[dy, -dx]/max(hypot(dx, dy), tiny(1.0_dp))
         end do
      end do
      do j = 1, size(normal, 2)
         len_e = norm2(normal(:, j))
         if (len_e > 0.0_dp) normal(:, j) = normal(:, j)/len_e
      end do
   end subroutine surface_normals

   !> Match every node of surface A with the surface-B node on its normal line.
   !! pair_b(i) = 0 where no B node lies within `tol` tangentially.
   subroutine match_surfaces(m, nodes_a, nodes_b, normal, tol, pair_b)
      type(model_t), intent(in) :: m
      integer, intent(in) :: nodes_a(:), nodes_b(:)
      real(dp), intent(in) :: normal(:, :)     !! (2, npoin) normals of surface B
      real(dp), intent(in) :: tol              !! accepted tangential offset
      integer, intent(out) :: pair_b(:)        !! (size(nodes_a))
      real(dp) :: d(2), t(2), off, best
      integer :: i, j, a, b
      pair_b = 0
      do i = 1, size(nodes_a)
         a = nodes_a(i)
         best = huge(1.0_dp)
         do j = 1, size(nodes_b)
            b = nodes_b(j)
            t = [normal(2, b), -normal(1, b)]
            d = m%coord(:, a) - m%coord(:, b)
            off = abs(dot_product(d, t))
            if (dot_product(d, normal(:, b)) < -tol) cycle   ! A would start inside B
            if (off < best) then
               best = off
               if (off <= tol) pair_b(i) = b
            end if
         end do
      end do
   end subroutine match_surfaces

   !> Lumped contact area of every node of the given edges (A1-A6), only
   !! over edges whose nodes are all flagged in `paired`.
   subroutine lumped_areas(m, ielem, iedge, paired, area)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)
      logical, intent(in) :: paired(:)         !! (npoin)
      real(dp), intent(out) :: area(:)         !! (npoin)
      integer, parameter :: ng = 5
      real(dp) :: posgp(ng), weigp(ng), shape(3), deriv(3), xy(2, 3), djac, w
      integer :: k, nd(3), nn, ig
      call gauss_legendre(ng, posgp, weigp)
      area = 0.0_dp
      do k = 1, size(ielem)
         call edge_nodes(m, ielem(k), iedge(k), nd, nn)
         if (.not. all(paired(nd(1:nn)))) cycle
         xy(:, 1:nn) = m%coord(:, nd(1:nn))
         do ig = 1, ng
            call edge_shape(nn, posgp(ig), shape(1:nn), deriv(1:nn))
            djac = hypot(dot_product(deriv(1:nn), xy(1, 1:nn)), dot_product(deriv(1:nn), xy(2, 1:nn)))
            if (m%ntype == NTYPE_AXISYMMETRIC) then
               w = two_pi*dot_product(shape(1:nn), xy(1, 1:nn))
            else
               w = m%mats(m%matno(ielem(k)))%thick
            end if
            area(nd(1:nn)) = area(nd(1:nn)) + shape(1:nn)*w*djac*weigp(ig)
         end do
      end do
   end subroutine lumped_areas

   !> Poisson's ratio at every node: that of the first element containing it.
   subroutine node_poisson(m, nu)
      type(model_t), intent(in) :: m
      real(dp), intent(out) :: nu(:)     !! (npoin)
      integer :: ie, k
      logical :: seen(m%npoin)
      seen = .false.
      nu = 0.0_dp
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            if (seen(m%lnods(k, ie))) cycle
            seen(m%lnods(k, ie)) = .true.
            nu(m%lnods(k, ie)) = m%mats(m%matno(ie))%poiss
         end do
      end do
   end subroutine node_poisson
   !> Build the pairs of every interface from its specification, check them
   !! and convert the interface constants to model units.  Problems go to
   !! `errors` / `warnings`, located at the spec's lines in `file`.
   subroutine define_contact(m, spec, file, errors, warnings)
      type(model_t), intent(inout) :: m
      type(iface_spec_t), intent(inout) :: spec(:)
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      type(error_list_t), intent(inout) :: warnings
      type(contact_pair_t), allocatable :: pairs(:)
      integer, allocatable :: ie_b(:), ik_b(:), ie_a(:), ik_a(:), nodes_a(:), nodes_b(:), pair_b(:), body(:), nolinks(:, :)
      real(dp), allocatable :: normal(:, :), area(:), nu(:), nu_pair(:)
      logical, allocatable :: paired(:), used_b(:)
      character(len=:), allocatable :: msg, list
      real(dp) :: size_model, tol, alpha
      integer :: i, k, j, np0, nbody, nbad, line
      logical :: have_b

      allocate (pairs(0), normal(2, m%npoin), area(m%npoin), nu(m%npoin), paired(m%npoin), used_b(m%npoin))
      allocate (nolinks(2, 0), body(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      call node_poisson(m, nu)
      size_model = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), maxval(m%coord(2, :)) - minval(m%coord(2, :)))
      if (allocated(m%contact%ifaces)) deallocate (m%contact%ifaces)
      allocate (m%contact%ifaces(size(spec)))
      do i = 1, size(spec)
         associate (s => spec(i))
            line = s%line
            if (s%law%law == LAW_ROUGH .and. .not. s%have_normal) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' (rough) has no NORMAL card '// &
                                 '(CN, M, CN2, M2)', file=file, line=line)
            end if
            if (.not. s%have_friction) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' has no FRICTION card '// &
                                 '(NONE, COULOMB mu, or FREDRIKSSON mu_m beta n)', file=file, line=line)
            end if
            if (s%npair == 0 .and. .not. (s%surf(1)%given .and. s%surf(2)%given)) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' needs SURFACE A and SURFACE B cards, '// &
                                 'or PAIRS', file=file, line=line)
               cycle
            end if
            np0 = size(pairs)

            ! surface B: edges, normals
            have_b = s%surf(2)%given
            normal = 0.0_dp
            if (have_b) then
               call surface_edges(m, s%surf(2), ie_b, ik_b, msg)
               if (len(msg) == 0) call check_listed(s%surf(2), ie_b, ik_b, msg)
               if (len(msg) > 0) then
                  call errors%add('E-SURFACE', 'CONTACT/SURFACE B: '//msg, file=file, line=s%surf(2)%line)
                  cycle
               end if
               call surface_normals(m, ie_b, ik_b, normal)
            end if
            tol = s%law%tol
            if (tol <= 0.0_dp) tol = 1.0e-6_dp*size_model

            if (s%npair > 0) then
               do k = 1, s%npair
                  call add_pair(s%pa(k), s%pb(k), s%pline(k))
                  associate (p => pairs(size(pairs)))
                     if (s%has_alpha(k)) then
                        alpha = s%palpha(k)*acos(-1.0_dp)/180.0_dp
                        p%t = [cos(alpha), sin(alpha)]
                        p%n = [-sin(alpha), cos(alpha)]
                     else if (have_b .and. norm2(normal(:, p%node_b)) > 0.0_dp) then
                        p%n = normal(:, p%node_b)
                        p%t = [p%n(2), -p%n(1)]
                     else if (have_b) then
                        call errors%add('E-CONTACT', 'CONTACT/PAIRS: node '//itoa(p%node_b)//' is not on surface B; '// &
                                          'give ALPHA', file=file, line=s%pline(k))
                     end if
                     if (s%has_g0(k)) then
                        p%g0 = s%pg0(k)
                     else
                        p%g0 = dot_product(m%coord(:, p%node_a) - m%coord(:, p%node_b), p%n)
                     end if
                  end associate
               end do
            end if
            if (s%surf(1)%given .and. have_b) then
               if (allocated(s%surf(1)%set_name)) then
                  call surface_edges(m, s%surf(1), ie_a, ik_a, msg)
                  if (len(msg) > 0) then
                     call errors%add('E-SURFACE', 'CONTACT/SURFACE A: '//msg, file=file, line=s%surf(1)%line)
                     cycle
                  end if
                  call unique_edge_nodes(ie_a, ik_a, nodes_a)
               else
                  nodes_a = s%surf(1)%nodes
                  call surface_edges(m, s%surf(1), ie_a, ik_a, msg)
                  if (len(msg) == 0) call check_listed(s%surf(1), ie_a, ik_a, msg)
                  if (len(msg) > 0) then
                     call errors%add('E-SURFACE', 'CONTACT/SURFACE A: '//msg, file=file, line=s%surf(1)%line)
                     cycle
                  end if
               end if
               call unique_edge_nodes(ie_b, ik_b, nodes_b)
               if (size(nodes_a) == 0) then
                  call errors%add('E-SURFACE', 'CONTACT/SURFACE A: no nodes', file=file, line=s%surf(1)%line)
                  cycle
               end if
               allocate (pair_b(size(nodes_a)))
               call match_surfaces(m, nodes_a, nodes_b, normal, tol, pair_b)
               if (any(pair_b == 0)) then
                  list = ''
                  nbad = 0
                  do k = 1, size(nodes_a)
                     if (pair_b(k) /= 0) cycle
                     nbad = nbad + 1
                     if (nbad <= 20) list = list//' '//itoa(nodes_a(k))
                  end do
                  if (nbad > 20) list = list//' ...'
                  call errors%add('E-UNMATCHED', 'CONTACT: interface '//itoa(i)//': '//itoa(nbad)// &
                                    ' node(s) of surface A have no partner on surface B within the tolerance '// &
                                    rtoa(tol)//' (tangential offset):'//list, file=file, line=s%surf(1)%line)
                  deallocate (pair_b)
                  cycle
               end if
               do k = 1, size(nodes_a)
                  call add_pair(nodes_a(k), pair_b(k), s%surf(1)%line)
                  associate (p => pairs(size(pairs)))
                     p%n = normal(:, p%node_b)
                     p%t = [p%n(2), -p%n(1)]
                     p%g0 = dot_product(m%coord(:, p%node_a) - m%coord(:, p%node_b), p%n)
                  end associate
               end do
               deallocate (pair_b)
            end if

            ! lumped areas from surface B over the paired zone; explicit areas win
            paired = .false.
            do k = np0 + 1, size(pairs)
               paired(pairs(k)%node_b) = .true.
            end do
            area = 0.0_dp
            if (have_b) call lumped_areas(m, ie_b, ik_b, paired, area)
            ! the node on the axis of a quadratic axisymmetric edge gets zero (not round-off)
            where (area < 1.0e-13_dp*maxval(area)) area = 0.0_dp
            j = 0
            do k = np0 + 1, size(pairs)
               pairs(k)%area = area(pairs(k)%node_b)
               if (k - np0 <= s%npair) then
                  j = j + 1
                  if (s%has_area(j)) pairs(k)%area = s%parea(j)
                  if (.not. s%has_area(j) .and. .not. have_b) call errors%add('E-CONTACT', &
                      'CONTACT/PAIRS: pair '//itoa(pairs(k)%node_a)//'-'//itoa(pairs(k)%node_b)//' needs an AREA '// &
                      '(or a SURFACE B to compute it from)', file=file, line=s%pline(j))
               end if
            end do

            ! per-pair Poisson ratio for R of eq. (2.8): mean of the two bodies
            allocate (nu_pair(size(pairs) - np0))
            do k = np0 + 1, size(pairs)
               nu_pair(k - np0) = 0.5_dp*(nu(pairs(k)%node_a) + nu(pairs(k)%node_b))
            end do
            m%contact%ifaces(i) = s%law
            if (s%law%law == LAW_ROUGH) then
               call convert_interface(m%contact%ifaces(i), nu_pair)
            else
               allocate (m%contact%ifaces(i)%r_t(size(nu_pair)))
               m%contact%ifaces(i)%r_t = 1.0_dp
            end if
            deallocate (nu_pair)
         end associate
      end do
      if (errors%n > 0) return

      ! checks across all pairs
      used_b = .false.
      do k = 1, size(pairs)
         associate (p => pairs(k))
            if (body(p%node_a) == body(p%node_b)) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ': both nodes belong to the same body (a contact spring joins two bodies)', &
                                 file=file, line=p%line)
            end if
            if (p%node_a == p%node_b) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' joins a node to itself', file=file, line=p%line)
            end if
            if (used_b(p%node_b)) then
               call errors%add('E-CONTACT', 'CONTACT: node '//itoa(p%node_b)//' of surface B is the partner of '// &
                                 'two nodes of surface A (overlapping surfaces or a too large tolerance)', &
                                 file=file, line=p%line)
            end if
            used_b(p%node_b) = .true.
            if (p%area <= 0.0_dp .and. .not. (m%ntype == 3 .and. m%coord(1, p%node_b) <= 1.0e-12_dp*size_model)) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' has no contact area (its node is on no edge of the paired zone of surface B)', &
                                 file=file, line=p%line)
            end if
            if (p%g0 < -tol_for(p)) then
               call warnings%add('W-PENETRATION', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' starts with a negative gap (penetration) '//rtoa(p%g0), file=file, line=p%line)
            end if
         end associate
      end do
      do k = 1, size(pairs)
         if (.not. used_b(pairs(k)%node_a)) cycle
         call errors%add('E-CONTACT', 'CONTACT: node '//itoa(pairs(k)%node_a)//' is on surface A and on '// &
                           'surface B (overlapping surfaces)', file=file, line=pairs(k)%line)
      end do
      m%contact%pairs = pairs
      m%contact%active = size(pairs) > 0
   contains
      subroutine add_pair(na, nb, ln)
         integer, intent(in) :: na, nb, ln
         type(contact_pair_t) :: p
         p%node_a = na
         p%node_b = nb
         p%iface = i
         p%line = ln
         p%position = m%coord(:, nb)
         pairs = [pairs, p]
      end subroutine add_pair

      pure real(dp) function tol_for(p)
         type(contact_pair_t), intent(in) :: p
         tol_for = 1.0e-9_dp*size_model + 0.0_dp*p%g0
      end function tol_for

      !> Every node listed for a surface must lie on one of its edges.
      subroutine check_listed(spec_s, ie, ik, text)
         type(surface_spec_t), intent(in) :: spec_s
         integer, intent(in) :: ie(:), ik(:)
         character(len=:), allocatable, intent(inout) :: text
         logical :: mark(m%npoin)
         integer :: q, nd(3), nn, nbad
         if (allocated(spec_s%set_name)) return
         mark = .false.
         do q = 1, size(ie)
            call edge_nodes(m, ie(q), ik(q), nd, nn)
            mark(nd(1:nn)) = .true.
         end do
         nbad = 0
         do q = 1, size(spec_s%nodes)
            if (mark(spec_s%nodes(q))) cycle
            nbad = nbad + 1
            if (nbad == 1) text = 'node(s) on no boundary edge formed by the listed nodes (a typo, a node '// &
                                  'of another body, or an interior node):'
            if (nbad <= 10) text = text//' '//itoa(spec_s%nodes(q))
         end do
      end subroutine check_listed

      subroutine unique_edge_nodes(ie, ik, nodes)
         integer, intent(in) :: ie(:), ik(:)
         integer, allocatable, intent(out) :: nodes(:)
         logical :: mark(m%npoin)
         integer :: q, nd(3), nn
         mark = .false.
         do q = 1, size(ie)
            call edge_nodes(m, ie(q), ik(q), nd, nn)
            mark(nd(1:nn)) = .true.
         end do
         nodes = pack([(q, q=1, m%npoin)], mark)
      end subroutine unique_edge_nodes
   end subroutine define_contact
end module contact_definition
