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
!!
!! Non-matching meshes (`MATCHING SEGMENT`) and rigid bodies (`RIGID`): every
!! node a of surface A (the slave side) is projected on the edges of surface
!! B or on the rigid profile (small sliding: the projection is done once).
!! Its area A_j is lumped from the edges of surface A, the side whose nodes
!! carry the pairs; its axes are the outward normal of B at the projection.
!! * Rigid profile: the pair joins a to its projection b, moved by the
!!   reference node; g0 = (x_a - x_b).n.
!! * Surface B: the pair joins a to surface B averaged over a's tributary zone
!!   (the mortar weights of a lumped slave side):
!!       u_b = sum_k w_k u_k,   w_k = int phi_a N_k(xi(s)) dA / int phi_a dA,
!!   phi_a the shape function of node a on its edges of A (int phi_a dA = A_j;
!!   the hat function where that vanishes, on the axis), N_k the shape
!!   functions of B at the projection xi(s) of each point s, and g0 the gap
!!   averaged in the same way.  Collocating the constraint at the node alone
!!   (w_k = N_k(xi_a)) would make the pressure oscillate from node to node by
!!   5-30 % (Hertz, ideal contact, meshes 0.5-2 times as fine); the averaged
!!   form transmits a uniform pressure exactly across non-matching meshes
!!   (contact patch test).  Ref: B. Wohlmuth, Discretization Methods and
!!   Iterative Solvers Based on Domain Decomposition, Springer 2001 (mortar
!!   methods); T. A. Laursen, Computational Contact and Impact Mechanics, 2002.
module contact_definition
   use kinds, only: dp, two_pi
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use sorting, only: insertion_sort
   use model, only: model_t, find_edge_set, find_node_set, NTYPE_AXISYMMETRIC
   use contact_types, only: contact_pair_t, interface_t, rigid_body_t, LAW_ROUGH, LAW_IDEAL, &
                            PAIR_NODE, PAIR_SEGMENT, PAIR_RIGID, MATCH_SEGMENT, RIGID_CIRCLE, MAX_PAIR_NODES
   use contact_laws, only: convert_interface
   use contact_spec, only: surface_spec_t, iface_spec_t
   use restraint_check, only: find_bodies
   use shape_2d, only: element_edge_nodes, nedges, edge_shape
   use quadrature, only: gauss_legendre
   implicit none
   private
   public :: surface_edges, edge_nodes, surface_normals, match_surfaces, &
             lumped_areas, node_poisson, node_modulus, define_contact, project_on_edge, project_on_rigid, &
             edge_scales

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
   !! over edges whose nodes are all flagged in `paired`.  On a quadratic
   !! axisymmetric edge with an end node on the axis that node's share is
   !! zero for a centred midside node; the coordinates of a deck (ten-column
   !! fields) rarely centre it to more than about 1e-9 of the edge, and the
   !! round-off share would make p = F/A of that pair meaningless, so it is
   !! given to the midside node (the edge's area is unchanged).
   subroutine lumped_areas(m, ielem, iedge, paired, area)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)
      logical, intent(in) :: paired(:)         !! (npoin)
      real(dp), intent(out) :: area(:)         !! (npoin)
      real(dp) :: xy(2, 3), share(3), chord
      integer :: k, nd(3), nn, ie
      area = 0.0_dp
      do k = 1, size(ielem)
         call edge_nodes(m, ielem(k), iedge(k), nd, nn)
         if (.not. all(paired(nd(1:nn)))) cycle
         xy(:, 1:nn) = m%coord(:, nd(1:nn))
         share = 0.0_dp
         share(1:nn) = edge_shares(m, ielem(k), xy(:, 1:nn), nn)
         if (m%ntype == NTYPE_AXISYMMETRIC .and. nn == 3) then
            ! edge order: the two end nodes, then the midside node
            chord = norm2(xy(:, 2) - xy(:, 1))
            do ie = 1, 2
               if (abs(xy(1, ie)) <= 1.0e-6_dp*chord) then
                  share(3) = share(3) + share(ie)
                  share(ie) = 0.0_dp
               end if
            end do
         end if
         area(nd(1:nn)) = area(nd(1:nn)) + share(1:nn)
      end do
   end subroutine lumped_areas

   !> Poisson's ratio at every node: that of the first element containing it.
   subroutine node_poisson(m, nu)
      type(model_t), intent(in) :: m
      real(dp), intent(out) :: nu(:)     !! (npoin)
      real(dp) :: e(size(nu))
      call node_modulus(m, e, nu)
   end subroutine node_poisson

   !> Young's modulus and Poisson's ratio at every node: those of the first
   !! element containing it (0 for a node of no element, e.g. a rigid body's
   !! reference node).
   subroutine node_modulus(m, e, nu)
      type(model_t), intent(in) :: m
      real(dp), intent(out) :: e(:)      !! (npoin)
      real(dp), intent(out) :: nu(:)     !! (npoin)
      integer :: ie, k
      logical :: seen(m%npoin)
      seen = .false.
      e = 0.0_dp
      nu = 0.0_dp
      do ie = 1, m%nelem
         do k = 1, m%nnode_e(ie)
            if (seen(m%lnods(k, ie))) cycle
            seen(m%lnods(k, ie)) = .true.
            e(m%lnods(k, ie)) = m%mats(m%matno(ie))%young
            nu(m%lnods(k, ie)) = m%mats(m%matno(ie))%poiss
         end do
      end do
   end subroutine node_modulus

   !> Consistent shares of an edge's area, int N_i w |J| dxi (5-point Gauss),
   !! w = 2 pi r (axisymmetric) or the thickness of element ielem (plane); nn
   !! nodes in edge order (start, end, mid) with coordinates xy.
   function edge_shares(m, ielem, xy, nn) result(share)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem, nn
      real(dp), intent(in) :: xy(:, :)           !! (2, nn)
      real(dp) :: share(nn)
      integer, parameter :: ng = 5
      real(dp) :: posgp(ng), weigp(ng), shape(3), deriv(3), djac, w
      integer :: ig
      call gauss_legendre(ng, posgp, weigp)
      share = 0.0_dp
      do ig = 1, ng
         call edge_shape(nn, posgp(ig), shape(1:nn), deriv(1:nn))
         djac = hypot(dot_product(deriv(1:nn), xy(1, 1:nn)), dot_product(deriv(1:nn), xy(2, 1:nn)))
         if (m%ntype == NTYPE_AXISYMMETRIC) then
            w = two_pi*dot_product(shape(1:nn), xy(1, 1:nn))
         else
            w = m%mats(m%matno(ielem))%thick
         end if
         share = share + shape(1:nn)*w*djac*weigp(ig)
      end do
   end function edge_shares

   !> Size of the contact elements at every node of the given edges (only
   !! edges whose nodes are all flagged in `paired`): the shortest adjacent
   !! edge (chord length between its end nodes) and the node's equal share
   !! (1/nn) of the adjacent edges' areas int w |J| dxi.  The share is
   !! positive also on the axis of an axisymmetric model, where the lumped
   !! area of a quadratic edge's end node is zero.
   subroutine edge_scales(m, ielem, iedge, paired, length, share)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)
      logical, intent(in) :: paired(:)         !! (npoin)
      real(dp), intent(out) :: length(:)       !! (npoin), 0 off the edges
      real(dp), intent(out) :: share(:)        !! (npoin)
      real(dp) :: xy(2, 3), ae, le
      integer :: k, nd(3), nn
      length = huge(1.0_dp)
      share = 0.0_dp
      do k = 1, size(ielem)
         call edge_nodes(m, ielem(k), iedge(k), nd, nn)
         if (.not. all(paired(nd(1:nn)))) cycle
         xy(:, 1:nn) = m%coord(:, nd(1:nn))
         ae = sum(edge_shares(m, ielem(k), xy(:, 1:nn), nn))
         le = norm2(xy(:, 2) - xy(:, 1))
         length(nd(1:nn)) = min(length(nd(1:nn)), le)
         share(nd(1:nn)) = share(nd(1:nn)) + ae/real(nn, dp)
      end do
      where (length > 0.5_dp*huge(1.0_dp)) length = 0.0_dp
   end subroutine edge_scales

   !> Nearest point of an edge to the point p (small-sliding projection).
   !! The edge has nn = 2 or 3 nodes with coordinates xy in (start, end, mid)
   !! order and lies on the boundary of a body to the left of start -> end, so
   !! its outward normal is (dy, -dx)/|.| (as in surface_normals).  xi is the
   !! edge coordinate of the foot of the perpendicular, clamped to [-1, 1];
   !! offset is how far p lies beyond the end of the edge along its tangent
   !! (0 when the foot falls on the edge).
   pure subroutine project_on_edge(nn, xy, p, xi, xb, normal, offset)
      integer, intent(in) :: nn
      real(dp), intent(in) :: xy(:, :)          !! (2, nn)
      real(dp), intent(in) :: p(2)
      real(dp), intent(out) :: xi, xb(2), normal(2), offset
      real(dp) :: shape(3), deriv(3), d(2), x1(2), f, fp, dxi, l2, tng(2), x2(2)
      integer :: it
      d = xy(:, 2) - xy(:, 1)
      l2 = max(dot_product(d, d), tiny(1.0_dp))
      xi = 2.0_dp*dot_product(p - xy(:, 1), d)/l2 - 1.0_dp
      if (nn == 3) then
         ! Newton on f(xi) = (x(xi) - p).x'(xi) = 0; x'' = (x_start + x_end - 2 x_mid)
         x2 = xy(:, 1) + xy(:, 2) - 2.0_dp*xy(:, 3)
         do it = 1, 30
            call edge_shape(3, xi, shape, deriv)
            x1 = matmul(xy(:, 1:3), deriv)
            f = dot_product(matmul(xy(:, 1:3), shape) - p, x1)
            fp = dot_product(x1, x1) + dot_product(matmul(xy(:, 1:3), shape) - p, x2)
            if (fp <= 0.0_dp) exit
            dxi = -f/fp
            xi = xi + dxi
            if (abs(dxi) <= 1.0e-14_dp) exit
         end do
      end if
      offset = 0.0_dp
      if (abs(xi) > 1.0_dp) then
         xi = sign(1.0_dp, xi)
         call edge_shape(nn, xi, shape(1:nn), deriv(1:nn))
         x1 = matmul(xy(:, 1:nn), deriv(1:nn))
         tng = x1/max(norm2(x1), tiny(1.0_dp))
         offset = abs(dot_product(p - matmul(xy(:, 1:nn), shape(1:nn)), tng))
      end if
      call edge_shape(nn, xi, shape(1:nn), deriv(1:nn))
      xb = matmul(xy(:, 1:nn), shape(1:nn))
      x1 = matmul(xy(:, 1:nn), deriv(1:nn))
      normal = [x1(2), -x1(1)]/max(norm2(x1), tiny(1.0_dp))
   end subroutine project_on_edge

   !> Nearest point of a rigid profile to p: xb, the profile's outward normal
   !! there, and the offset beyond the profile's ends (0 on the profile).  A
   !! polyline is listed with the body on its left; among its segments the one
   !! nearest to p with an offset within tol wins.  ok is false if p is the
   !! centre of a circle (no normal).
   pure subroutine project_on_rigid(rb, p, tol, xb, normal, offset, ok)
      type(rigid_body_t), intent(in) :: rb
      real(dp), intent(in) :: p(2), tol
      real(dp), intent(out) :: xb(2), normal(2), offset
      logical, intent(out) :: ok
      real(dp) :: d(2), r, best, xi, yb(2), nb(2), off, dist
      integer :: k
      ok = .true.
      if (rb%shape == RIGID_CIRCLE) then
         d = p - rb%centre
         r = norm2(d)
         ok = r > 0.0_dp
         normal = [0.0_dp, 1.0_dp]
         if (ok) normal = d/r
         xb = rb%centre + rb%radius*normal
         offset = 0.0_dp
         return
      end if
      best = huge(1.0_dp)
      offset = huge(1.0_dp)
      xb = rb%xy(:, 1)
      normal = [0.0_dp, 1.0_dp]
      do k = 1, size(rb%xy, 2) - 1
         call project_on_edge(2, rb%xy(:, k:k + 1), p, xi, yb, nb, off)
         dist = norm2(p - yb)
         if (off > tol .and. offset <= tol) cycle
         if ((off <= tol .and. offset > tol) .or. dist < best .or. (offset > tol .and. off < offset)) then
            best = dist
            offset = off
            xb = yb
            normal = nb
         end if
      end do
   end subroutine project_on_rigid

   !> Build the pairs of every interface from the model's contact
   !! specification, check them and convert the interface constants to model
   !! units.  Problems go to `errors` / `warnings`, located at the spec's
   !! lines in the deck.
   subroutine define_contact(m, errors, warnings)
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: errors
      type(error_list_t), intent(inout) :: warnings
      type(contact_pair_t), allocatable :: pairs(:)
      integer, allocatable :: ie_b(:), ik_b(:), ie_a(:), ik_a(:), nodes_a(:), nodes_b(:), pair_b(:), body(:), nolinks(:, :)
      real(dp), allocatable :: normal(:, :), area(:), nu(:), nu_pair(:), young(:), lenv(:), share(:)
      logical, allocatable :: paired(:), used_b(:), master(:), in_elem(:)
      character(len=:), allocatable :: msg, list, file
      real(dp) :: size_model, tol, alpha, w
      integer :: i, k, j, np0, nbody, nbad, line, ie, q
      logical :: have_b, is_rigid, is_segment

      allocate (pairs(0), normal(2, m%npoin), area(m%npoin), nu(m%npoin), paired(m%npoin), used_b(m%npoin))
      allocate (nolinks(2, 0), body(m%npoin), young(m%npoin), lenv(m%npoin), share(m%npoin), master(m%npoin))
      allocate (in_elem(m%npoin))
      call find_bodies(m, nolinks, body, nbody)
      call node_modulus(m, young, nu)
      size_model = max(maxval(m%coord(1, :)) - minval(m%coord(1, :)), maxval(m%coord(2, :)) - minval(m%coord(2, :)))
      file = m%deck_file
      m%contact%rigids = m%contact_spec%rigids
      m%contact%opts = m%contact_spec%opts
      in_elem = .false.
      do ie = 1, m%nelem
         in_elem(m%lnods(1:m%nnode_e(ie), ie)) = .true.
      end do
      call check_rigids()
      if (allocated(m%contact%ifaces)) deallocate (m%contact%ifaces)
      allocate (m%contact%ifaces(size(m%contact_spec%ifaces)))
      do i = 1, size(m%contact_spec%ifaces)
         associate (s => m%contact_spec%ifaces(i))
            line = s%line
            if (s%law%law == LAW_ROUGH .and. .not. s%have_normal) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' (rough) has no NORMAL card '// &
                                 '(CN, M, CN2, M2)', file=file, line=line)
            end if
            if (.not. s%have_friction) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' has no FRICTION card '// &
                                 '(NONE, COULOMB mu, or FREDRIKSSON mu_m beta n)', file=file, line=line)
            end if
            is_rigid = s%law%rigid > 0
            is_segment = s%law%matching == MATCH_SEGMENT .and. .not. is_rigid
            if (is_rigid) then
               if (s%surf(2)%given) call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)//' has a RIGID body '// &
                                 'and a SURFACE B: the rigid body is side B, give only SURFACE A (the deformable '// &
                                 'surface facing it)', file=file, line=s%surf(2)%line)
               if (size(s%pairs) > 0) call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)//' has a RIGID body: '// &
                                 'its pairs are built from SURFACE A, PAIRS cannot be given', file=file, line=s%pairs(1)%line)
               if (s%have_matching) call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)//': MATCHING applies '// &
                                 'to a SURFACE B; the nodes of SURFACE A are always projected on a rigid profile', &
                                 file=file, line=s%matching_line)
               if (.not. s%surf(1)%given) then
                  call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)//' has a RIGID body but no SURFACE A '// &
                                    '(the deformable surface facing it)', file=file, line=line)
                  cycle
               end if
               if (s%surf(2)%given .or. size(s%pairs) > 0 .or. s%have_matching) cycle
            else if (is_segment) then
               if (size(s%pairs) > 0) call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//': PAIRS are '// &
                                 'node-to-node; MATCHING SEGMENT builds its pairs from SURFACE A and SURFACE B', &
                                 file=file, line=s%pairs(1)%line)
               if (.not. (s%surf(1)%given .and. s%surf(2)%given)) then
                  call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' (MATCHING SEGMENT) needs SURFACE A '// &
                                    'and SURFACE B cards', file=file, line=line)
                  cycle
               end if
               if (size(s%pairs) > 0) cycle
            else if (size(s%pairs) == 0 .and. .not. (s%surf(1)%given .and. s%surf(2)%given)) then
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//' needs SURFACE A and SURFACE B cards, '// &
                                 'PAIRS, or SURFACE A and a RIGID body', file=file, line=line)
               cycle
            end if
            np0 = size(pairs)
            tol = s%law%tol
            if (tol <= 0.0_dp) tol = 1.0e-6_dp*size_model

            if (is_rigid .or. is_segment) then
               if (.not. projected_pairs(s)) cycle
            else
               ! ---- node-to-node pairs (the paper)
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

               if (size(s%pairs) > 0) then
                  do k = 1, size(s%pairs)
                     call add_pair(s%pairs(k)%node_a, s%pairs(k)%node_b, s%pairs(k)%line)
                     associate (p => pairs(size(pairs)))
                        if (s%pairs(k)%has_alpha) then
                           alpha = s%pairs(k)%alpha*acos(-1.0_dp)/180.0_dp
                           p%t = [cos(alpha), sin(alpha)]
                           p%n = [-sin(alpha), cos(alpha)]
                        else if (have_b .and. norm2(normal(:, p%node_b)) > 0.0_dp) then
                           p%n = normal(:, p%node_b)
                           p%t = [p%n(2), -p%n(1)]
                        else if (have_b) then
                           call errors%add('E-CONTACT', 'CONTACT/PAIRS: node '//itoa(p%node_b)//' is not on surface B; '// &
                                             'give ALPHA', file=file, line=s%pairs(k)%line)
                        end if
                        if (s%pairs(k)%has_g0) then
                           p%g0 = s%pairs(k)%g0
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
                                       rtoa(tol)//' (tangential offset):'//list//'; for meshes that do not match '// &
                                       'node for node use MATCHING SEGMENT', file=file, line=s%surf(1)%line)
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
               lenv = 0.0_dp
               share = 0.0_dp
               if (have_b) then
                  call lumped_areas(m, ie_b, ik_b, paired, area)
                  call edge_scales(m, ie_b, ik_b, paired, lenv, share)
               end if
               ! the node on the axis of a quadratic axisymmetric edge gets zero (not round-off)
               where (area < 1.0e-13_dp*maxval(area)) area = 0.0_dp
               j = 0
               do k = np0 + 1, size(pairs)
                  pairs(k)%area = area(pairs(k)%node_b)
                  pairs(k)%length = lenv(pairs(k)%node_b)
                  pairs(k)%share = share(pairs(k)%node_b)
                  if (k - np0 <= size(s%pairs)) then
                     j = j + 1
                     if (s%pairs(j)%has_area) pairs(k)%area = s%pairs(j)%area
                     if (.not. s%pairs(j)%has_area .and. .not. have_b) call errors%add('E-CONTACT', &
                         'CONTACT/PAIRS: pair '//itoa(pairs(k)%node_a)//'-'//itoa(pairs(k)%node_b)//' needs an AREA '// &
                         '(or a SURFACE B to compute it from)', file=file, line=s%pairs(j)%line)
                  end if
                  if (pairs(k)%share <= 0.0_dp) pairs(k)%share = pairs(k)%area
                  if (pairs(k)%length <= 0.0_dp) then
                     ! explicit pair off any edge: the length whose strip has the pair's area
                     w = m%mats(1)%thick
                     if (m%ntype == NTYPE_AXISYMMETRIC) w = two_pi*m%coord(1, pairs(k)%node_b)
                     if (w > 0.0_dp) then
                        pairs(k)%length = pairs(k)%area/w
                     else
                        pairs(k)%length = sqrt(pairs(k)%area)
                     end if
                  end if
               end do
            end if

            ! per-pair Poisson ratio for R of eq. (2.8): mean of the two bodies;
            ! contact modulus E* for the ideal law's penalty scale
            allocate (nu_pair(size(pairs) - np0))
            do k = np0 + 1, size(pairs)
               associate (p => pairs(k))
                  if (p%kind == PAIR_RIGID) then
                     nu_pair(k - np0) = nu(p%node_a)
                     p%estar = young(p%node_a)/(1.0_dp - nu(p%node_a)**2)
                  else
                     nu_pair(k - np0) = 0.5_dp*(nu(p%node_a) + nu(p%nodes(2)))
                     p%estar = 1.0_dp/((1.0_dp - nu(p%node_a)**2)/young(p%node_a) + &
                                       (1.0_dp - nu(p%nodes(2))**2)/young(p%nodes(2)))
                  end if
               end associate
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
      master = .false.
      do k = 1, size(pairs)
         associate (p => pairs(k))
            if (p%kind /= PAIR_RIGID) then
               if (body(p%node_a) == body(p%nodes(2))) then
                  call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                    ': both nodes belong to the same body (a contact spring joins two bodies)', &
                                    file=file, line=p%line)
               end if
               master(p%nodes(2:p%nn)) = .true.
            end if
            if (p%node_a == p%node_b) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' joins a node to itself', file=file, line=p%line)
            end if
            if (p%kind == PAIR_NODE) then
               if (used_b(p%node_b)) then
                  call errors%add('E-CONTACT', 'CONTACT: node '//itoa(p%node_b)//' of surface B is the partner of '// &
                                    'two nodes of surface A (overlapping surfaces or a too large tolerance)', &
                                    file=file, line=p%line)
               end if
               used_b(p%node_b) = .true.
            end if
            q = p%node_b
            if (p%kind /= PAIR_NODE) q = p%node_a
            if (p%area <= 0.0_dp .and. .not. (m%ntype == 3 .and. m%coord(1, q) <= 1.0e-12_dp*size_model)) then
               call errors%add('E-CONTACT', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' has no contact area (its node is on no edge of the paired zone of surface '// &
                                 merge('B', 'A', p%kind == PAIR_NODE)//')', file=file, line=p%line)
            end if
            if (p%g0 < -tol_for(p)) then
               call warnings%add('W-PENETRATION', 'CONTACT: pair '//itoa(p%node_a)//'-'//itoa(p%node_b)// &
                                 ' starts with a negative gap (penetration) '//rtoa(p%g0), file=file, line=p%line)
            end if
         end associate
      end do
      do k = 1, size(pairs)
         if (.not. master(pairs(k)%node_a)) cycle
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
         p%nodes(1:2) = [na, nb]
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

      !> Checks of the rigid bodies: the reference node belongs to no element,
      !! a polyline has two or more distinct vertices.
      subroutine check_rigids()
         integer :: r, v
         do r = 1, size(m%contact%rigids)
            associate (rb => m%contact%rigids(r))
               if (in_elem(rb%node)) call errors%add('E-RIGID', 'CONTACT/RIGID: reference node '//itoa(rb%node)// &
                                                     ' belongs to an element; the reference node of a rigid body '// &
                                                     'must be a node of no element', file=file, line=rb%line)
               if (rb%shape /= RIGID_CIRCLE) then
                  if (size(rb%xy, 2) < 2) then
                     call errors%add('E-RIGID', 'CONTACT/RIGID: a polyline profile needs at least two vertices '// &
                                       '(X, Y cards after the RIGID card), found '//itoa(size(rb%xy, 2)), &
                                       file=file, line=rb%line)
                  else
                     do v = 1, size(rb%xy, 2) - 1
                        if (norm2(rb%xy(:, v + 1) - rb%xy(:, v)) <= 1.0e-12_dp*size_model) then
                           call errors%add('E-RIGID', 'CONTACT/RIGID: vertices '//itoa(v)//' and '//itoa(v + 1)// &
                                             ' of the profile coincide', file=file, line=rb%line)
                        end if
                     end do
                  end if
               end if
            end associate
         end do
      end subroutine check_rigids

      !> Pairs of an interface whose side B is a rigid profile or the edges of
      !! surface B (MATCHING SEGMENT): every node of surface A is projected;
      !! areas and element sizes come from the edges of surface A.
      logical function projected_pairs(s) result(ok)
         type(iface_spec_t), intent(in) :: s
         type(contact_pair_t) :: p
         real(dp) :: xy(2, 3), xb(2), nrm(2), off, xi, dist, best, bxb(2), bn(2), gavg
         integer :: ka, kb, nd(3), nn, bk, a
         logical :: okp
         ok = .false.
         call surface_edges(m, s%surf(1), ie_a, ik_a, msg)
         if (len(msg) > 0) then
            call errors%add('E-SURFACE', 'CONTACT/SURFACE A: '//msg, file=file, line=s%surf(1)%line)
            return
         end if
         call unique_edge_nodes(ie_a, ik_a, nodes_a)
         ! lumped areas of surface A (all its nodes are paired)
         paired = .false.
         paired(nodes_a) = .true.
         call lumped_areas(m, ie_a, ik_a, paired, area)
         where (area < 1.0e-13_dp*maxval(area)) area = 0.0_dp
         if (s%law%rigid == 0) then
            call surface_edges(m, s%surf(2), ie_b, ik_b, msg)
            if (len(msg) > 0) then
               call errors%add('E-SURFACE', 'CONTACT/SURFACE B: '//msg, file=file, line=s%surf(2)%line)
               return
            end if
         end if
         list = ''
         nbad = 0
         do ka = 1, size(nodes_a)
            a = nodes_a(ka)
            p = contact_pair_t()
            p%node_a = a
            p%iface = i
            p%line = s%surf(1)%line
            if (s%law%rigid > 0) then
               associate (rb => m%contact%rigids(s%law%rigid))
                  call project_on_rigid(rb, m%coord(:, a), tol, xb, nrm, off, okp)
                  if (.not. okp .or. off > tol) then
                     call unmatched(a)
                     cycle
                  end if
                  p%kind = PAIR_RIGID
                  p%nn = 2
                  p%nodes(1:2) = [a, rb%node]
                  p%node_b = rb%node
                  p%w(1:2) = 1.0_dp
               end associate
            else
               best = huge(1.0_dp)
               bk = 0
               bxb = 0.0_dp
               bn = 0.0_dp
               do kb = 1, size(ie_b)
                  call edge_nodes(m, ie_b(kb), ik_b(kb), nd, nn)
                  xy(:, 1:nn) = m%coord(:, nd(1:nn))
                  call project_on_edge(nn, xy(:, 1:nn), m%coord(:, a), xi, xb, nrm, off)
                  if (off > tol) cycle
                  dist = norm2(m%coord(:, a) - xb)
                  if (dist < best) then
                     best = dist
                     bk = kb
                     bxb = xb
                     bn = nrm
                  end if
               end do
               if (bk == 0) then
                  call unmatched(a)
                  cycle
               end if
               xb = bxb
               nrm = bn
               p%kind = PAIR_SEGMENT
               p%nodes(1) = a
               p%w(1) = 1.0_dp
               call tributary_weights(a, nrm, p, gavg, okp)
               if (.not. okp) cycle
            end if
            p%n = nrm
            p%t = [nrm(2), -nrm(1)]
            if (p%kind == PAIR_SEGMENT) then
               p%g0 = gavg
            else
               p%g0 = dot_product(m%coord(:, a) - xb, nrm)
            end if
            p%position = xb
            pairs = [pairs, p]
         end do
         if (nbad > 0) then
            if (nbad > 20) list = list//' ...'
            call errors%add('E-UNMATCHED', 'CONTACT: interface '//itoa(i)//': '//itoa(nbad)// &
                              ' node(s) of surface A do not face '// &
                              trim(merge('the rigid profile', 'surface B        ', s%law%rigid > 0))// &
                              ' (their projection falls beyond its ends by more than '//rtoa(tol)//'):'//list, &
                              file=file, line=s%surf(1)%line)
            return
         end if
         ! side B must face surface A: opposite outward normals
         call surface_normals(m, ie_a, ik_a, normal)
         nbad = 0
         list = ''
         do k = np0 + 1, size(pairs)
            if (dot_product(pairs(k)%n, normal(:, pairs(k)%node_a)) <= 0.0_dp) cycle
            call unmatched(pairs(k)%node_a)
         end do
         if (nbad > 0) then
            if (nbad > 20) list = list//' ...'
            if (s%law%rigid > 0) then
               call errors%add('E-RIGID', 'CONTACT: interface '//itoa(i)//': '//itoa(nbad)//' node(s) of '// &
                                 'surface A lie where the rigid profile faces away from them (its outward normal '// &
                                 'points the way of surface A''s own):'//list//'; list the vertices with the rigid '// &
                                 'body on their left (anticlockwise around the body)', file=file, line=s%surf(1)%line)
            else
               call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//': '//itoa(nbad)//' node(s) of '// &
                                 'surface A face the back of surface B (both outward normals point the same way):'// &
                                 list, file=file, line=s%surf(1)%line)
            end if
            return
         end if
         ! areas (computed above) and sizes from surface A
         call edge_scales(m, ie_a, ik_a, paired, lenv, share)
         do k = np0 + 1, size(pairs)
            pairs(k)%area = area(pairs(k)%node_a)
            pairs(k)%length = lenv(pairs(k)%node_a)
            pairs(k)%share = share(pairs(k)%node_a)
         end do
         ok = .true.
      end function projected_pairs

      subroutine unmatched(a)
         integer, intent(in) :: a
         nbad = nbad + 1
         if (nbad <= 20) list = list//' '//itoa(a)
      end subroutine unmatched

      !> Master nodes and weights of slave node a averaged over its tributary
      !! zone (the edges of surface A at a, weighted by a's hat function and
      !! the area element w |J|), and the gap averaged the same way along the
      !! pair's normal nrm.  Points of the zone that face no edge of B are left
      !! out.  ok is false (and an error reported) if more master nodes than a
      !! pair can hold are involved.
      subroutine tributary_weights(a, nrm, p, gavg, ok)
         integer, intent(in) :: a
         real(dp), intent(in) :: nrm(2)
         type(contact_pair_t), intent(inout) :: p
         real(dp), intent(out) :: gavg
         logical, intent(out) :: ok
         integer, parameter :: ng = 5
         real(dp) :: posgp(ng), weigp(ng), sh(3), dv(3), xy(2, 3), xg(2), dw, hat, xi, xb(2), nb(2), off, dist, best
         real(dp) :: bxi, bxb(2), total, mw(MAX_PAIR_NODES - 1), xyb(2, 3), sg, area_scale
         real(dp), allocatable :: brk(:)
         integer :: ke, nd(3), nn, ja, ig, kb, bnd(3), bnn, ndb(3), nnb, r, q, nm, mnodes(MAX_PAIR_NODES - 1), ib, pass
         logical :: full, use_hat
         area_scale = size_model**2
         call gauss_legendre(ng, posgp, weigp)
         do pass = 1, 2
            use_hat = pass == 2
            nm = 0
            total = 0.0_dp
            gavg = 0.0_dp
            mw = 0.0_dp
            mnodes = 0
            full = .false.
            do ke = 1, size(ie_a)
               call edge_nodes(m, ie_a(ke), ik_a(ke), nd, nn)
               ja = findloc(nd(1:nn), a, 1)
               if (ja == 0) cycle
               xy(:, 1:nn) = m%coord(:, nd(1:nn))
               ! break the edge where nodes of B project on it: the integrand is
               ! smooth between these points, and 5-point Gauss rules on the
               ! pieces integrate it exactly on straight edges
               brk = [-1.0_dp, 1.0_dp]
               do kb = 1, size(ie_b)
                  call edge_nodes(m, ie_b(kb), ik_b(kb), ndb, nnb)
                  do r = 1, nnb
                     call project_on_edge(nn, xy(:, 1:nn), m%coord(:, ndb(r)), xi, xb, nb, off)
                     if (off > 0.0_dp .or. abs(xi) >= 1.0_dp) cycle
                     if (any(abs(brk - xi) <= 1.0e-12_dp)) cycle
                     brk = [brk, xi]
                  end do
               end do
               call insertion_sort(brk)
               do ib = 1, size(brk) - 1
                  do ig = 1, ng
                     sg = 0.5_dp*(brk(ib) + brk(ib + 1)) + 0.5_dp*(brk(ib + 1) - brk(ib))*posgp(ig)
                     call edge_shape(nn, sg, sh(1:nn), dv(1:nn))
                     xg = matmul(xy(:, 1:nn), sh(1:nn))
                     dw = hypot(dot_product(dv(1:nn), xy(1, 1:nn)), dot_product(dv(1:nn), xy(2, 1:nn)))*weigp(ig)* &
                          0.5_dp*(brk(ib + 1) - brk(ib))
                     if (m%ntype == NTYPE_AXISYMMETRIC) then
                        dw = dw*two_pi*xg(1)
                     else
                        dw = dw*m%mats(m%matno(ie_a(ke)))%thick
                     end if
                     ! a's shape function (they sum to 1 and integrate to the lumped
                     ! areas, so a uniform pressure is transferred exactly); its hat
                     ! function where that integral vanishes (axis node of a quadratic
                     ! axisymmetric edge)
                     if (use_hat) then
                        select case (ja)
                        case (1)
                           hat = 0.5_dp*(1.0_dp - sg)
                        case (2)
                           hat = 0.5_dp*(1.0_dp + sg)
                        case default
                           hat = 1.0_dp - abs(sg)
                        end select
                     else
                        hat = sh(ja)
                        ! the mid node of a quadratic edge takes over the shape
                        ! function of an end node of zero area (on the axis): that
                        ! node carries no force, and without this its share of
                        ! the transfer to B would be lost (the patch test fails
                        ! near the axis)
                        if (ja == 3) then
                           if (area(nd(1)) <= 0.0_dp) hat = hat + sh(1)
                           if (area(nd(2)) <= 0.0_dp) hat = hat + sh(2)
                        end if
                     end if
                     best = huge(1.0_dp)
                     bnn = 0
                     do kb = 1, size(ie_b)
                        call edge_nodes(m, ie_b(kb), ik_b(kb), ndb, nnb)
                        xyb(:, 1:nnb) = m%coord(:, ndb(1:nnb))
                        call project_on_edge(nnb, xyb(:, 1:nnb), xg, xi, xb, nb, off)
                        if (off > tol) cycle
                        dist = norm2(xg - xb)
                        if (dist < best) then
                           best = dist
                           bnn = nnb
                           bnd = ndb
                           bxi = xi
                           bxb = xb
                        end if
                     end do
                     if (bnn == 0) cycle
                     call edge_shape(bnn, bxi, sh(1:bnn), dv(1:bnn))
                     do r = 1, bnn
                        q = findloc(mnodes(1:nm), bnd(r), 1)
                        if (q == 0) then
                           if (nm == size(mnodes)) then
                              full = .true.
                              cycle
                           end if
                           nm = nm + 1
                           mnodes(nm) = bnd(r)
                           q = nm
                        end if
                        mw(q) = mw(q) + hat*dw*sh(r)
                     end do
                     total = total + hat*dw
                     gavg = gavg + hat*dw*dot_product(xg - bxb, nrm)
                  end do
               end do
            end do
            if (total > 1.0e-12_dp*area_scale) exit
         end do
         ok = .not. full .and. total > 0.0_dp .and. nm > 0
         if (full) then
            call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(i)//': node '//itoa(a)//' of surface A faces '// &
                              'more than '//itoa(MAX_PAIR_NODES - 1)//' nodes of surface B; with MATCHING SEGMENT '// &
                              'surface A should be the finer of the two', file=file, line=p%line)
            return
         end if
         if (.not. ok) then
            call unmatched(a)
            return
         end if
         mw(1:nm) = mw(1:nm)/total
         gavg = gavg/total
         where (abs(mw(1:nm)) < 1.0e-14_dp) mw(1:nm) = 0.0_dp
         p%nn = 1 + nm
         p%nodes(2:1 + nm) = mnodes(1:nm)
         p%w(2:1 + nm) = mw(1:nm)
         p%node_b = mnodes(maxloc(mw(1:nm), 1))
      end subroutine tributary_weights
   end subroutine define_contact
end module contact_definition
