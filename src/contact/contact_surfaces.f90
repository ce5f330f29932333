!> Contact surfaces: the element edges of a surface, its outward normals,
!! lumped areas and the sizes of its contact elements.
!!
!! A contact surface is a set of element edges on the boundary of one body
!! (given as a named edge set, or derived from a list or set of nodes: the
!! boundary edges all of whose nodes are in the list).  Edges are numbered
!! as in model/topology (edge k of an element from corner k to corner k+1,
!! the body on its left, nodes in (start, end, mid) order), so the outward
!! normal of an edge is (dy, -dx)/|.| along start -> end.
!!
!! Lumped areas (eqs. 3.22, 3.26, 4.2, appendix A1-A6, SPEC §3.2): row-sum
!! lumping of the edge "mass" matrix,
!!     A_j = sum over edges e of j of  int G_j(xi) w(xi) |J(xi)| dxi,
!! with w = t (plane) or 2 pi r (axisymmetric), the arc-length Jacobian |J|,
!! over the edges whose nodes are all paired (the common contact zone), so
!! that the A_j of a surface sum to its nominal area.
!!
!! Units: coordinates, lengths and areas in the model's units (areas are
!! length x thickness in plane problems, length x 2 pi r in axisymmetry).
!! Arrays indexed by node are (npoin) or (2, npoin).
!!
!! Ref: Altenbach & Buczkowski, eqs. (3.22), (3.26), appendix (A1)-(A6);
!!      Hinton & Owen (1977), routine LOADPS (edge integrals).
module contact_surfaces
   use kinds, only: dp, two_pi
   use strings, only: itoa
   use model, only: model_t, find_edge_set, find_node_set, NTYPE_AXISYMMETRIC
   use contact_spec, only: surface_spec_t
   use topology, only: element_edge_nodes, nedges
   use shape_2d, only: edge_shape
   use quadrature, only: gauss_legendre
   implicit none
   private

   public :: edge_nodes, surface_edges, boundary_edges_of, check_listed, surface_nodes, &
         surface_normals, &
             lumped_areas, edge_shares, edge_scales

contains

   !> Global nodes of edge iedge of element ie, in (start, end, mid) order.
   pure subroutine edge_nodes(m, ie, iedge, nodes, nn)
      type(model_t), intent(in) :: m          !! lnods, nnode_e used
      integer, intent(in) :: ie               !! element
      integer, intent(in) :: iedge            !! edge of the element, 1..nedges
      integer, intent(out) :: nodes(3)        !! node numbers; nodes(3) = 0 on a 2-node edge
      integer, intent(out) :: nn              !! nodes on the edge: 2 or 3 (0: no such edge)
      integer :: loc(3)
      call element_edge_nodes(m%nnode_e(ie), iedge, loc, nn)
      nodes = 0
      nodes(1:nn) = m%lnods(loc(1:nn), ie)
   end subroutine edge_nodes

   !> The boundary edges of a surface: those of its edge set, or the boundary
   !! edges all of whose nodes are in its node set or node list.
   pure subroutine surface_edges(m, spec, ielem, iedge, msg)
      type(model_t), intent(in) :: m                       !! mesh and named sets
      type(surface_spec_t), intent(in) :: spec             !! the surface as the deck gives it
      integer, allocatable, intent(out) :: ielem(:)        !! element of each edge
      integer, allocatable, intent(out) :: iedge(:)        !! its edge number (model/topology)
      character(len=:), allocatable, intent(out) :: msg    !! '' on success, else the reason
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

   !> Boundary edges (edges of exactly one element) all of whose nodes are in
   !! `nodes`, ordered by their end nodes (lowest first).
   pure subroutine boundary_edges_of(m, nodes, ielem, iedge)
      type(model_t), intent(in) :: m
      integer, intent(in) :: nodes(:)                      !! node numbers (out-of-range
                                                           !! ones are ignored)
      integer, allocatable, intent(out) :: ielem(:)        !! element of each edge
      integer, allocatable, intent(out) :: iedge(:)        !! its edge number
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
         if (i > 1) then
            shared = shared .or. (key1(idx(i)) == key1(idx(i - 1)) .and. key2(idx(i)) == &
                                  key2(idx(i - 1)))
         end if
         if (i < n) then
            shared = shared .or. (key1(idx(i)) == key1(idx(i + 1)) .and. key2(idx(i)) == &
                                  key2(idx(i + 1)))
         end if
         if (shared) cycle
         j = j + 1
         ielem(j) = ce(idx(i))
         iedge(j) = ck(idx(i))
      end do
      ielem = ielem(1:j)
      iedge = iedge(1:j)
   end subroutine boundary_edges_of

   !> Order idx so that (k1, k2)(idx) is lexicographically sorted (merge sort).
   pure subroutine sort_pairs(k1, k2, idx)
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

   !> Every node listed for a surface must lie on one of its edges: msg gets
   !! the reason and the first ten such nodes ('' unchanged when all do, or
   !! when the surface is a named set).
   pure subroutine check_listed(m, spec, ielem, iedge, msg)
      type(model_t), intent(in) :: m
      type(surface_spec_t), intent(in) :: spec           !! the surface as the deck gives it
      integer, intent(in) :: ielem(:), iedge(:)          !! its edges (surface_edges)
      character(len=:), allocatable, intent(inout) :: msg
      logical :: mark(m%npoin)
      integer :: q, nd(3), nn, nbad
      if (allocated(spec%set_name)) return
      mark = .false.
      do q = 1, size(ielem)
         call edge_nodes(m, ielem(q), iedge(q), nd, nn)
         mark(nd(1:nn)) = .true.
      end do
      nbad = 0
      do q = 1, size(spec%nodes)
         if (mark(spec%nodes(q))) cycle
         nbad = nbad + 1
         if (nbad == 1) msg = &
               'node(s) on no boundary edge formed by the listed nodes (a typo, a node '// &
                              'of another body, or an interior node):'
         if (nbad <= 10) msg = msg//' '//itoa(spec%nodes(q))
      end do
   end subroutine check_listed

   !> The nodes of a set of edges, each once, in increasing order.
   pure subroutine surface_nodes(m, ielem, iedge, nodes)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)          !! edge iedge(k) of element ielem(k)
      integer, allocatable, intent(out) :: nodes(:)
      logical :: mark(m%npoin)
      integer :: q, nd(3), nn
      mark = .false.
      do q = 1, size(ielem)
         call edge_nodes(m, ielem(q), iedge(q), nd, nn)
         mark(nd(1:nn)) = .true.
      end do
      nodes = pack([(q, q=1, m%npoin)], mark)
   end subroutine surface_nodes

   !> Outward unit normal of a body at every node of its surface edges: the
   !! mean of the adjacent edges' normals weighted by their chord lengths,
   !! each evaluated at the node (exact for curved quadratic edges).  Nodes
   !! off the surface get 0.
   pure subroutine surface_normals(m, ielem, iedge, normal)
      type(model_t), intent(in) :: m              !! coord [length], lnods
      integer, intent(in) :: ielem(:), iedge(:)   !! the surface's edges (surface_edges)
      real(dp), intent(out) :: normal(:, :)       !! (2, npoin) unit outward normals [-]
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

   !> Lumped contact area of every node of the given edges (A1-A6), only
   !! over edges whose nodes are all flagged in `paired`.  On a quadratic
   !! axisymmetric edge with an end node on the axis that node's share is
   !! zero for a centred midside node; the coordinates of a deck (ten-column
   !! fields) rarely centre it to more than about 1e-9 of the edge, and the
   !! round-off share would make p = F/A of that pair meaningless, so it is
   !! given to the midside node (the edge's area is unchanged).
   !!
   !! Ref: Altenbach & Buczkowski, eqs. (3.22), (3.26), (A1)-(A6).
   pure subroutine lumped_areas(m, ielem, iedge, paired, area)
      type(model_t), intent(in) :: m              !! coord [length], ntype, thickness
                                                  !! of each element's material
      integer, intent(in) :: ielem(:), iedge(:)   !! the surface's edges (surface_edges)
      logical, intent(in) :: paired(:)            !! (npoin) nodes of the contact zone
      real(dp), intent(out) :: area(:)            !! (npoin) A_j [length^2]: length
                                                  !! x thickness, or x 2 pi r
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

   !> Consistent shares of an edge's area, int N_i w |J| dxi (5-point Gauss),
   !! w = 2 pi r (axisymmetric) or the thickness of element ielem (plane); nn
   !! nodes in edge order (start, end, mid) with coordinates xy.
   pure function edge_shares(m, ielem, xy, nn) result(share)
      type(model_t), intent(in) :: m              !! ntype, thickness of the element's material
      integer, intent(in) :: ielem                !! element the edge belongs to
      integer, intent(in) :: nn                   !! nodes on the edge: 2 or 3
      real(dp), intent(in) :: xy(:, :)            !! (2, nn) coordinates [length]
      real(dp) :: share(nn)                       !! share of each node [length^2]
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
   pure subroutine edge_scales(m, ielem, iedge, paired, length, share)
      type(model_t), intent(in) :: m              !! coord [length], ntype, thicknesses
      integer, intent(in) :: ielem(:), iedge(:)   !! the surface's edges (surface_edges)
      logical, intent(in) :: paired(:)            !! (npoin) nodes of the contact zone
      real(dp), intent(out) :: length(:)          !! (npoin) shortest adjacent chord
                                                  !! [length], 0 off the edges
      real(dp), intent(out) :: share(:)           !! (npoin) equal share of the
                                                  !! adjacent areas [length^2]
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
end module contact_surfaces
