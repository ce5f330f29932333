!> Contact pairing: which point of side B each node of side A is paired
!! with, and the pairs of an interface built from its specification.
!!
!! Three algorithms, each callable on its own:
!!
!! * Node to node (the paper; `match_nodes`): every node of surface A is
!!   matched with the node of surface B that lies on its normal line
!!   (tangential offset within a tolerance); the local axes (t, n) of a pair
!!   are those of surface B at its node (outward normal of body B, averaged
!!   over the adjacent edges), and the initial gap is g0 = (x_a - x_b).n
!!   (eq. 3.8).
!! * Projection on the edges of surface B (`MATCHING SEGMENT`;
!!   `project_on_edge`, `nearest_edge`, `tributary_weights`): node a of
!!   surface A (the slave side) is paired with surface B averaged over a's
!!   tributary zone (the mortar weights of a lumped slave side):
!!       u_b = sum_k w_k u_k,   w_k = int phi_a N_k(xi(s)) dA / int phi_a dA,
!!   phi_a the shape function of node a on its edges of A (int phi_a dA = A_j;
!!   the hat function where that vanishes, on the axis), N_k the shape
!!   functions of B at the projection xi(s) of each point s, and g0 the gap
!!   averaged in the same way.  Collocating the constraint at the node alone
!!   (w_k = N_k(xi_a)) would make the pressure oscillate from node to node by
!!   5-30 % (Hertz, ideal contact, meshes 0.5-2 times as fine); the averaged
!!   form transmits a uniform pressure exactly across non-matching meshes
!!   (contact patch test).
!! * Projection on a rigid profile (`RIGID`; `project_on_rigid`): the pair
!!   joins a to its projection b, moved by the body's reference node;
!!   g0 = (x_a - x_b).n.
!!
!! Projections are done once, on the undeformed meshes (small sliding).  With
!! a projection the pair's area is lumped from the edges of surface A, the
!! side whose nodes carry the pairs; its axes are the outward normal of B at
!! the projection.  `node_pairs` and `projected_pairs` build the pairs of
!! one interface and report what is wrong with it at its deck lines.
!!
!! Units: coordinates, distances, tolerances and gaps in the model's length
!! unit; areas in length^2 (see contact_surfaces); normals and weights are
!! dimensionless.
!!
!! Ref: Altenbach & Buczkowski, eq. (3.8); B. Wohlmuth, Discretization
!!      Methods and Iterative Solvers Based on Domain Decomposition, Springer
!!      2001 (mortar methods); T. A. Laursen, Computational Contact and Impact
!!      Mechanics, Springer 2002.
module contact_pairing
   use kinds, only: dp, two_pi
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use sorting, only: insertion_sort
   use model, only: model_t, NTYPE_AXISYMMETRIC
   use contact_types, only: contact_pair_t, rigid_body_t, PAIR_SEGMENT, PAIR_RIGID, RIGID_CIRCLE, &
         MAX_PAIR_NODES
   use contact_spec, only: iface_spec_t
   use contact_surfaces, only: edge_nodes, surface_edges, check_listed, surface_nodes, &
         surface_normals, &
                               lumped_areas, edge_scales
   use shape_2d, only: edge_shape
   use quadrature, only: gauss_legendre
   implicit none
   private

   public :: match_nodes, project_on_edge, project_on_rigid, nearest_edge, tributary_weights, &
             node_pairs, projected_pairs
   public :: TRIB_OK, TRIB_NONE, TRIB_FULL

   ! outcome of tributary_weights
   integer, parameter :: TRIB_OK = 0     !! weights found
   integer, parameter :: TRIB_NONE = 1   !! the tributary zone faces no edge of B
   integer, parameter :: TRIB_FULL = 2   !! more master nodes than a pair holds (MAX_PAIR_NODES - 1)

   ! outcome of pairing one node by projection
   integer, parameter :: NODE_PAIRED = 0     !! the pair is built
   integer, parameter :: NODE_UNMATCHED = 1  !! the node faces nothing within the tolerance
   !> Code of the error "a node of A faces more nodes of B than a pair holds":
   !! the one a MATCHING SEGMENT interface cures by swapping its sides.
   character(len=*), parameter, public :: E_COARSE_SIDE = 'E-SEGMENT-SIDE'
   integer, parameter :: NODE_REJECTED = 2   !! the node cannot be paired (error reported)

contains

   ! ------------------------------------------------------------------ the algorithms

   !> Match every node of surface A with the surface-B node on its normal
   !! line: among the nodes of B that A does not start inside of (by more than
   !! tol along B's normal), the one of smallest tangential offset, if that
   !! offset is within tol.
   pure subroutine match_nodes(coord, nodes_a, nodes_b, normal, tol, pair_b)
      real(dp), intent(in) :: coord(:, :)      !! (2, npoin) node coordinates [length]
      integer, intent(in) :: nodes_a(:)        !! nodes of surface A
      integer, intent(in) :: nodes_b(:)        !! nodes of surface B
      real(dp), intent(in) :: normal(:, :)     !! (2, npoin) unit outward normals
                                               !! of surface B at its nodes
      real(dp), intent(in) :: tol              !! accepted tangential offset and
                                               !! initial penetration [length]
      integer, intent(out) :: pair_b(:)        !! (size(nodes_a)) partner in B
                                               !! of each node of A, 0 if none
      real(dp) :: d(2), t(2), off, best
      integer :: i, j, a, b
      pair_b = 0
      do i = 1, size(nodes_a)
         a = nodes_a(i)
         best = huge(1.0_dp)
         do j = 1, size(nodes_b)
            b = nodes_b(j)
            t = [normal(2, b), -normal(1, b)]
            d = coord(:, a) - coord(:, b)
            off = abs(dot_product(d, t))
            if (dot_product(d, normal(:, b)) < -tol) cycle   ! A would start inside B
            if (off < best) then
               best = off
               if (off <= tol) pair_b(i) = b
            end if
         end do
      end do
   end subroutine match_nodes

   !> Nearest point of an edge to the point p (small-sliding projection).
   !! The edge has nn = 2 or 3 nodes with coordinates xy in (start, end, mid)
   !! order and lies on the boundary of a body to the left of start -> end, so
   !! its outward normal is (dy, -dx)/|.| (as in surface_normals).  On a
   !! quadratic edge the foot of the perpendicular is found by Newton's
   !! method on (x(xi) - p).x'(xi) = 0, started from the chord.
   pure subroutine project_on_edge(nn, xy, p, xi, xb, normal, offset)
      integer, intent(in) :: nn                 !! nodes on the edge: 2 (linear) or 3 (quadratic)
      real(dp), intent(in) :: xy(:, :)          !! (2, nn) node coordinates
                                                !! [length], (start, end, mid)
      real(dp), intent(in) :: p(2)              !! the point [length]
      real(dp), intent(out) :: xi               !! edge coordinate of the foot, clamped to [-1, 1]
      real(dp), intent(out) :: xb(2)            !! the edge's point at xi [length]
      real(dp), intent(out) :: normal(2)        !! unit outward normal of the edge at xi
      real(dp), intent(out) :: offset           !! how far p lies beyond the
                                                !! end of the edge along its
                                                !! tangent [length]; 0 when the foot falls on the
                                                !! edge
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

   !> Nearest point of a rigid profile to p.  A polyline is listed with the
   !! body on its left (outward normal (dy, -dx)/|.| of each segment); among
   !! its segments the one nearest to p with an offset within tol wins, or,
   !! if none is within tol, the one of smallest offset.  A circle's outward
   !! normal is radial.
   pure subroutine project_on_rigid(rb, p, tol, xb, normal, offset, ok)
      type(rigid_body_t), intent(in) :: rb      !! the profile (polyline vertices
                                                !! or circle) [length]
      real(dp), intent(in) :: p(2)              !! the point [length]
      real(dp), intent(in) :: tol               !! accepted offset beyond a segment's end [length]
      real(dp), intent(out) :: xb(2)            !! nearest point of the profile [length]
      real(dp), intent(out) :: normal(2)        !! unit outward normal of the profile at xb
      real(dp), intent(out) :: offset           !! distance beyond the profile's
                                                !! ends along its tangent
                                                !! [length]; 0 on the profile (always 0 on a circle)
      logical, intent(out) :: ok                !! false if p is the centre of a circle (no normal)
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
         if ((off <= tol .and. offset > tol) .or. dist < best .or. &
               (offset > tol .and. off < offset)) then
            best = dist
            offset = off
            xb = yb
            normal = nb
         end if
      end do
   end subroutine project_on_rigid

   !> Nearest projection of p on a set of edges: among the edges on which p
   !! falls within tol of the ends (project_on_edge), the one whose foot is
   !! nearest to p (the first of equals).  k = 0 if p faces none.
   pure subroutine nearest_edge(m, ielem, iedge, p, tol, k, xi, xb, normal)
      type(model_t), intent(in) :: m                !! coord [length], lnods
      integer, intent(in) :: ielem(:), iedge(:)     !! the edges (surface_edges)
      real(dp), intent(in) :: p(2)                  !! the point [length]
      real(dp), intent(in) :: tol                   !! accepted offset beyond an edge's end [length]
      integer, intent(out) :: k                     !! index of the nearest edge
                                                    !! in ielem/iedge, 0 if none
      real(dp), intent(out) :: xi                   !! edge coordinate of the foot
                                                    !! on edge k, in [-1, 1]
      real(dp), intent(out) :: xb(2)                !! the foot [length]
      real(dp), intent(out) :: normal(2)            !! unit outward normal of edge k at the foot
      real(dp) :: xy(2, 3), xi_k, xb_k(2), n_k(2), off, dist, best
      integer :: kb, nd(3), nn
      best = huge(1.0_dp)
      k = 0
      xi = 0.0_dp
      xb = 0.0_dp
      normal = 0.0_dp
      do kb = 1, size(ielem)
         call edge_nodes(m, ielem(kb), iedge(kb), nd, nn)
         xy(:, 1:nn) = m%coord(:, nd(1:nn))
         call project_on_edge(nn, xy(:, 1:nn), p, xi_k, xb_k, n_k, off)
         if (off > tol) cycle
         dist = norm2(p - xb_k)
         if (dist < best) then
            best = dist
            k = kb
            xi = xi_k
            xb = xb_k
            normal = n_k
         end if
      end do
   end subroutine nearest_edge

   !> Master nodes and weights of slave node a averaged over its tributary
   !! zone (the edges of surface A at a, weighted by a's shape function and
   !! the area element w |J|), and the gap averaged the same way along the
   !! pair's normal nrm.  Points of the zone that face no edge of B are left
   !! out.  Each edge of A is cut where nodes of B project on it, and each
   !! piece integrated with 5 Gauss points (exact on straight edges).  Where
   !! a's shape function integrates to nothing (the end node on the axis of a
   !! quadratic axisymmetric edge) its hat function is used instead.
   pure subroutine tributary_weights(m, ie_a, ik_a, ie_b, ik_b, area_a, a, nrm, tol, size_model, &
                                     nm, mnodes, mw, &
                                     gavg, status)
      type(model_t), intent(in) :: m                !! coord [length], ntype, thicknesses
      integer, intent(in) :: ie_a(:), ik_a(:)       !! edges of surface A
      integer, intent(in) :: ie_b(:), ik_b(:)       !! edges of surface B
      real(dp), intent(in) :: area_a(:)             !! (npoin) lumped areas of surface A [length^2]
                                                    !! (lumped_areas; 0 marks the axis node)
      integer, intent(in) :: a                      !! the slave node (a node of surface A)
      real(dp), intent(in) :: nrm(2)                !! unit normal of the pair, along
                                                    !! which the gap is taken
      real(dp), intent(in) :: tol                   !! accepted offset beyond an edge of B [length]
      real(dp), intent(in) :: size_model            !! model size [length]: a zone of area below
                                                    !! 1e-12 size_model^2 counts as empty
      integer, intent(out) :: nm                    !! number of master nodes
      integer, intent(out) :: mnodes(MAX_PAIR_NODES - 1)  !! master nodes (nodes of B), 1..nm
      real(dp), intent(out) :: mw(MAX_PAIR_NODES - 1)     !! their weights w_k, summing to 1
      real(dp), intent(out) :: gavg                 !! averaged initial gap [length]
      integer, intent(out) :: status                !! TRIB_OK, TRIB_NONE or TRIB_FULL
      integer, parameter :: ng = 5
      real(dp) :: posgp(ng), weigp(ng), sh(3), dv(3), xy(2, 3), xg(2), dw, hat, xi, xb(2), nb(2), &
            total, sg, total_g
      real(dp), allocatable :: brk(:)
      integer :: ke, nd(3), nn, ja, ig, kb, bnd(3), bnn, r, q, ib, pass
      logical :: full, use_hat

      call gauss_legendre(ng, posgp, weigp)
      do pass = 1, 2
         use_hat = pass == 2
         nm = 0
         total = 0.0_dp
         total_g = 0.0_dp
         gavg = 0.0_dp
         mw = 0.0_dp
         mnodes = 0
         full = .false.
         do ke = 1, size(ie_a)
            call edge_nodes(m, ie_a(ke), ik_a(ke), nd, nn)
            ja = findloc(nd(1:nn), a, 1)
            if (ja == 0) cycle
            xy(:, 1:nn) = m%coord(:, nd(1:nn))
            brk = break_points(m, ie_b, ik_b, nn, xy(:, 1:nn))
            do ib = 1, size(brk) - 1
               do ig = 1, ng
                  sg = 0.5_dp*(brk(ib) + brk(ib + 1)) + 0.5_dp*(brk(ib + 1) - brk(ib))*posgp(ig)
                  call edge_shape(nn, sg, sh(1:nn), dv(1:nn))
                  xg = matmul(xy(:, 1:nn), sh(1:nn))
                  dw = hypot(dot_product(dv(1:nn), xy(1, 1:nn)), &
                             dot_product(dv(1:nn), xy(2, 1:nn)))*weigp(ig)* &
                       0.5_dp*(brk(ib + 1) - brk(ib))
                  if (m%ntype == NTYPE_AXISYMMETRIC) then
                     dw = dw*two_pi*xg(1)
                  else
                     dw = dw*m%mats(m%matno(ie_a(ke)))%thick
                  end if
                  hat = slave_weight(ja, sg, sh(1:nn), area_a(nd(1:2)), use_hat)
                  call nearest_edge(m, ie_b, ik_b, xg, tol, kb, xi, xb, nb)
                  if (kb == 0) cycle
                  call edge_nodes(m, ie_b(kb), ik_b(kb), bnd, bnn)
                  call edge_shape(bnn, xi, sh(1:bnn), dv(1:bnn))
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
                  ! the gap averaged with the positive part of the weight: a corner's shape
                  ! function of a quadratic edge is negative over part of it, and a curved
                  ! surface touching B at the node (all gaps >= 0) got a negative average
                  total_g = total_g + max(hat, 0.0_dp)*dw
                  gavg = gavg + max(hat, 0.0_dp)*dw*dot_product(xg - xb, nrm)
               end do
            end do
         end do
         if (total > 1.0e-12_dp*size_model**2) exit
      end do
      if (full) then
         status = TRIB_FULL
      else if (.not. (total > 0.0_dp .and. nm > 0)) then
         status = TRIB_NONE
      else
         status = TRIB_OK
         mw(1:nm) = mw(1:nm)/total
         gavg = gavg/total_g
         where (abs(mw(1:nm)) < 1.0e-14_dp) mw(1:nm) = 0.0_dp
      end if
   end subroutine tributary_weights

   !> Edge coordinates in (-1, 1) where the nodes of a set of edges project
   !! on an edge of nn nodes at xy, with -1 and 1, in increasing order: the
   !! integrand of the tributary weights is smooth between them.
   pure function break_points(m, ielem, iedge, nn, xy) result(brk)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ielem(:), iedge(:)     !! the edges whose nodes are
                                                    !! projected (surface B)
      integer, intent(in) :: nn                     !! nodes of the edge cut: 2 or 3
      real(dp), intent(in) :: xy(:, :)              !! (2, nn) its coordinates [length]
      real(dp), allocatable :: brk(:)
      real(dp) :: xi, xb(2), nb(2), off
      integer :: kb, r, nd(3), nnb
      brk = [-1.0_dp, 1.0_dp]
      do kb = 1, size(ielem)
         call edge_nodes(m, ielem(kb), iedge(kb), nd, nnb)
         do r = 1, nnb
            call project_on_edge(nn, xy, m%coord(:, nd(r)), xi, xb, nb, off)
            if (off > 0.0_dp .or. abs(xi) >= 1.0_dp) cycle
            if (any(abs(brk - xi) <= 1.0e-12_dp)) cycle
            brk = [brk, xi]
         end do
      end do
      call insertion_sort(brk)
   end function break_points

   !> Weight of slave node ja of an edge at edge coordinate sg: its shape
   !! function (they sum to one and integrate to the lumped areas, so a
   !! uniform pressure is transferred exactly), or its hat function where
   !! that integral vanishes (axis node of a quadratic axisymmetric edge).
   !! The mid node of a quadratic edge takes over the shape function of an
   !! end node of zero area (on the axis): that node carries no force, and
   !! without this its share of the transfer to B would be lost (the patch
   !! test fails near the axis).
   pure real(dp) function slave_weight(ja, sg, sh, area_end, use_hat) result(hat)
      integer, intent(in) :: ja                 !! position of the slave node
                                                !! on the edge (start, end, mid)
      real(dp), intent(in) :: sg                !! edge coordinate
      real(dp), intent(in) :: sh(:)             !! shape functions of the edge at sg
      real(dp), intent(in) :: area_end(2)       !! lumped areas of the edge's end nodes [length^2]
      logical, intent(in) :: use_hat            !! the hat function instead of the shape function
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
         if (ja == 3) then
            if (area_end(1) <= 0.0_dp) hat = hat + sh(1)
            if (area_end(2) <= 0.0_dp) hat = hat + sh(2)
         end if
      end if
   end function slave_weight

   ! ------------------------------------------------------------------ node-to-node pairs of an
   ! interface

   !> Node-to-node pairs of interface iface (the paper): its explicit PAIRS,
   !! then every node of SURFACE A matched with a node of SURFACE B; lumped
   !! areas from surface B over the paired zone (an explicit AREA wins).
   !! Appended to `pairs`; ok is false where the interface cannot be built
   !! (its errors reported).
   subroutine node_pairs(m, s, iface, tol, file, pairs, errors, ok)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s                          !! the interface as
                                                                   !! the deck gives it
      integer, intent(in) :: iface                                 !! its number
      real(dp), intent(in) :: tol                                  !! pairing tolerance [length]
      character(len=*), intent(in) :: file                         !! deck file, for messages
      type(contact_pair_t), allocatable, intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer, allocatable :: ie_b(:), ik_b(:)
      real(dp), allocatable :: normal(:, :)
      character(len=:), allocatable :: msg
      integer :: np0
      logical :: have_b

      ok = .false.
      np0 = size(pairs)
      have_b = s%surf(2)%given
      allocate (normal(2, m%npoin))
      normal = 0.0_dp
      if (have_b) then
         call surface_edges(m, s%surf(2), ie_b, ik_b, msg)
         if (len(msg) == 0) call check_listed(m, s%surf(2), ie_b, ik_b, msg)
         if (len(msg) > 0) then
            call errors%add('E-SURFACE', 'CONTACT/SURFACE B: '//msg, file=file, line=s%surf(2)%line)
            return
         end if
         call surface_normals(m, ie_b, ik_b, normal)
      else
         allocate (ie_b(0), ik_b(0))
      end if
      call explicit_pairs(m, s, iface, have_b, normal, file, pairs, errors)
      if (s%surf(1)%given .and. have_b) then
         call matched_pairs(m, s, iface, ie_b, ik_b, normal, tol, file, pairs, errors, ok)
         if (.not. ok) return
      end if
      call node_pair_areas(m, s, have_b, ie_b, ik_b, np0, file, pairs, errors)
      ok = .true.
   end subroutine node_pairs

   !> A node-to-node pair of interface iface, its axes and gap still to be set.
   pure function new_pair(coord, iface, na, nb, line) result(p)
      real(dp), intent(in) :: coord(:, :)       !! (2, npoin) [length]
      integer, intent(in) :: iface, na, nb      !! interface, node a, node b
      integer, intent(in) :: line               !! deck line that creates the pair
      type(contact_pair_t) :: p
      p%node_a = na
      p%node_b = nb
      p%nodes(1:2) = [na, nb]
      p%iface = iface
      p%line = line
      p%position = coord(:, nb)
   end function new_pair

   !> The explicit PAIRS of an interface: axes from ALPHA (degrees from the
   !! x axis to t) or the normal of surface B at node b; gap G0 or (x_a - x_b).n.
   subroutine explicit_pairs(m, s, iface, have_b, normal, file, pairs, errors)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s
      integer, intent(in) :: iface
      logical, intent(in) :: have_b                 !! the interface has a SURFACE B
      real(dp), intent(in) :: normal(:, :)          !! (2, npoin) normals of surface B (0 off it)
      character(len=*), intent(in) :: file
      type(contact_pair_t), allocatable, intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      type(contact_pair_t) :: p
      type(contact_pair_t), allocatable :: new(:)
      real(dp) :: alpha
      integer :: k
      allocate (new(size(s%pairs)))   ! filled, then appended once: linear in the pairs
      do k = 1, size(s%pairs)
         p = new_pair(m%coord, iface, s%pairs(k)%node_a, s%pairs(k)%node_b, s%pairs(k)%line)
         if (s%pairs(k)%has_alpha) then
            alpha = s%pairs(k)%alpha*acos(-1.0_dp)/180.0_dp
            p%t = [cos(alpha), sin(alpha)]
            p%n = [-sin(alpha), cos(alpha)]
         else if (have_b .and. norm2(normal(:, p%node_b)) > 0.0_dp) then
            p%n = normal(:, p%node_b)
            p%t = [p%n(2), -p%n(1)]
         else if (have_b) then
            call errors%add('E-CONTACT', 'CONTACT/PAIRS: node '//itoa(p%node_b)// &
                            ' is not on surface B; '// &
                            'give ALPHA', file=file, line=s%pairs(k)%line)
         end if
         if (s%pairs(k)%has_g0) then
            p%g0 = s%pairs(k)%g0
         else
            p%g0 = dot_product(m%coord(:, p%node_a) - m%coord(:, p%node_b), p%n)
         end if
         new(k) = p
      end do
      pairs = [pairs, new]
   end subroutine explicit_pairs

   !> Every node of SURFACE A paired with its node of SURFACE B (match_nodes);
   !! ok is false (errors reported) if surface A is wrong or a node of it has
   !! no partner.
   subroutine matched_pairs(m, s, iface, ie_b, ik_b, normal, tol, file, pairs, errors, ok)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s
      integer, intent(in) :: iface
      integer, intent(in) :: ie_b(:), ik_b(:)       !! edges of surface B
      real(dp), intent(in) :: normal(:, :)          !! (2, npoin) normals of surface B
      real(dp), intent(in) :: tol                   !! pairing tolerance [length]
      character(len=*), intent(in) :: file
      type(contact_pair_t), allocatable, intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer, allocatable :: ie_a(:), ik_a(:), nodes_a(:), nodes_b(:), pair_b(:)
      character(len=:), allocatable :: msg, list
      type(contact_pair_t) :: p
      type(contact_pair_t), allocatable :: new(:)
      integer :: k, nbad, np0

      ok = .false.
      call surface_edges(m, s%surf(1), ie_a, ik_a, msg)
      if (allocated(s%surf(1)%set_name)) then
         if (len(msg) == 0) call surface_nodes(m, ie_a, ik_a, nodes_a)
      else
         nodes_a = s%surf(1)%nodes
         if (len(msg) == 0) call check_listed(m, s%surf(1), ie_a, ik_a, msg)
      end if
      if (len(msg) > 0) then
         call errors%add('E-SURFACE', 'CONTACT/SURFACE A: '//msg, file=file, line=s%surf(1)%line)
         return
      end if
      call surface_nodes(m, ie_b, ik_b, nodes_b)
      if (size(nodes_a) == 0) then
         call errors%add('E-SURFACE', 'CONTACT/SURFACE A: no nodes', file=file, line=s%surf(1)%line)
         return
      end if
      allocate (pair_b(size(nodes_a)))
      call match_nodes(m%coord, nodes_a, nodes_b, normal, tol, pair_b)
      if (any(pair_b == 0)) then
         list = ''
         nbad = 0
         do k = 1, size(nodes_a)
            if (pair_b(k) /= 0) cycle
            call note_node(nbad, list, nodes_a(k))
         end do
         if (nbad > 20) list = list//' ...'
         call errors%add('E-UNMATCHED', 'CONTACT: interface '//itoa(iface)//': '//itoa(nbad)// &
                         ' node(s) of surface A have no partner on surface B within the &
                         &tolerance '// &
                         rtoa(tol)//' (tangential offset):'//list// &
                         '; for meshes that do not match '// &
                         'node for node use MATCHING SEGMENT', file=file, line=s%surf(1)%line)
         return
      end if
      np0 = size(pairs)
      allocate (new(size(nodes_a)))   ! filled, then appended once: linear in the pairs
      do k = 1, size(nodes_a)
         p = new_pair(m%coord, iface, nodes_a(k), pair_b(k), s%surf(1)%line)
         p%n = normal(:, p%node_b)
         p%t = [p%n(2), -p%n(1)]
         p%g0 = dot_product(m%coord(:, p%node_a) - m%coord(:, p%node_b), p%n)
         new(k) = p
      end do
      pairs = [pairs, new]
      ! the surfaces must be the faces of the two bodies that look at each other
      ok = facing(m, s, iface, ie_a, ik_a, pairs(np0 + 1:), file, errors)
   end subroutine matched_pairs

   !> Areas and element sizes of the node-to-node pairs pairs(np0+1:): lumped
   !! from surface B over the paired zone; an explicit AREA wins, and an
   !! explicit pair off any edge gets the length whose strip has its area.
   subroutine node_pair_areas(m, s, have_b, ie_b, ik_b, np0, file, pairs, errors)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s
      logical, intent(in) :: have_b                 !! the interface has a SURFACE B
      integer, intent(in) :: ie_b(:), ik_b(:)       !! its edges
      integer, intent(in) :: np0                    !! pairs of earlier interfaces
      character(len=*), intent(in) :: file
      type(contact_pair_t), intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      real(dp), allocatable :: area(:), lenv(:), share(:)
      logical, allocatable :: paired(:)
      real(dp) :: w
      integer :: k, j

      allocate (area(m%npoin), lenv(m%npoin), share(m%npoin), paired(m%npoin))
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
                'CONTACT/PAIRS: pair '//itoa(pairs(k)%node_a)//'-'//itoa(pairs(k)%node_b)// &
                ' needs an AREA '// &
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
   end subroutine node_pair_areas

   ! ------------------------------------------------------------------ projected pairs of an
   ! interface

   !> Pairs of interface iface whose side B is a rigid profile or the edges
   !! of surface B (MATCHING SEGMENT): every node of surface A is projected;
   !! areas and element sizes come from the edges of surface A.  Appended to
   !! `pairs`; ok is false where the interface cannot be built (its errors
   !! reported).
   subroutine projected_pairs(m, s, iface, tol, size_model, file, pairs, errors, ok)
      type(model_t), intent(in) :: m                               !! mesh; contact%rigids
                                                                   !! for a rigid side B
      type(iface_spec_t), intent(in) :: s                          !! the interface as
                                                                   !! the deck gives it
      integer, intent(in) :: iface                                 !! its number
      real(dp), intent(in) :: tol                                  !! pairing tolerance [length]
      real(dp), intent(in) :: size_model                           !! model size [length]
      character(len=*), intent(in) :: file                         !! deck file, for messages
      type(contact_pair_t), allocatable, intent(inout) :: pairs(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer, allocatable :: ie_a(:), ik_a(:), ie_b(:), ik_b(:), nodes_a(:)
      real(dp), allocatable :: area(:), lenv(:), share(:)
      logical, allocatable :: paired(:)
      character(len=:), allocatable :: msg, list, hint
      type(contact_pair_t) :: p
      type(contact_pair_t), allocatable :: new(:)
      integer :: ka, k, np0, nbad, outcome, nnew

      ok = .false.
      np0 = size(pairs)
      allocate (area(m%npoin), lenv(m%npoin), share(m%npoin), paired(m%npoin))
      call surface_edges(m, s%surf(1), ie_a, ik_a, msg)
      if (len(msg) > 0) then
         call errors%add('E-SURFACE', 'CONTACT/SURFACE A: '//msg, file=file, line=s%surf(1)%line)
         return
      end if
      call surface_nodes(m, ie_a, ik_a, nodes_a)
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
      else
         allocate (ie_b(0), ik_b(0))
      end if
      list = ''
      nbad = 0
      allocate (new(size(nodes_a)))   ! filled, then appended once: linear in the pairs
      nnew = 0
      do ka = 1, size(nodes_a)
         p = contact_pair_t()
         p%node_a = nodes_a(ka)
         p%iface = iface
         p%line = s%surf(1)%line
         if (s%law%rigid > 0) then
            call rigid_pair(m%coord, m%contact%rigids(s%law%rigid), tol, p, outcome)
         else
            call segment_pair(m, ie_a, ik_a, ie_b, ik_b, area, tol, size_model, file, p, errors, &
                              outcome)
         end if
         if (outcome == NODE_PAIRED) then
            nnew = nnew + 1
            new(nnew) = p
         else if (outcome == NODE_UNMATCHED) then
            call note_node(nbad, list, p%node_a)
         end if
      end do
      pairs = [pairs, new(1:nnew)]
      if (nbad > 0) then
         if (nbad > 20) list = list//' ...'
         hint = ''
         if (s%law%rigid <= 0) hint = '; surface A must lie within the extent of B: name only &
            &the part of A that faces B, or make the shorter surface A (the pairs'' normal &
            &follows B, whichever body is on top)'
         call errors%add('E-UNMATCHED', 'CONTACT: interface '//itoa(iface)//': '//itoa(nbad)// &
                         ' node(s) of surface A do not face '// &
                         trim(merge('the rigid profile', 'surface B        ', s%law%rigid > 0))// &
                         ' (their projection falls beyond its ends by more than '//rtoa(tol)// &
                         '):'//list//hint, file=file, line=s%surf(1)%line)
         return
      end if
      if (.not. facing(m, s, iface, ie_a, ik_a, pairs(np0 + 1:), file, errors)) return
      ! areas (computed above) and sizes from surface A
      call edge_scales(m, ie_a, ik_a, paired, lenv, share)
      do k = np0 + 1, size(pairs)
         pairs(k)%area = area(pairs(k)%node_a)
         pairs(k)%length = lenv(pairs(k)%node_a)
         pairs(k)%share = share(pairs(k)%node_a)
      end do
      ok = .true.
   end subroutine projected_pairs

   !> The pair of node p%node_a with a rigid profile: NODE_UNMATCHED when the
   !! node's projection falls beyond the profile's ends by more than tol.
   pure subroutine rigid_pair(coord, rb, tol, p, outcome)
      real(dp), intent(in) :: coord(:, :)            !! (2, npoin) [length]
      type(rigid_body_t), intent(in) :: rb           !! the profile (side B)
      real(dp), intent(in) :: tol                    !! pairing tolerance [length]
      type(contact_pair_t), intent(inout) :: p       !! node_a set; kind, nodes,
                                                     !! axes, g0, position set here
      integer, intent(out) :: outcome                !! NODE_PAIRED or NODE_UNMATCHED
      real(dp) :: xb(2), nrm(2), off
      logical :: okp
      associate (a => p%node_a)
         call project_on_rigid(rb, coord(:, a), tol, xb, nrm, off, okp)
         outcome = NODE_UNMATCHED
         if (.not. okp .or. off > tol) return
         outcome = NODE_PAIRED
         p%kind = PAIR_RIGID
         p%nn = 2
         p%nodes(1:2) = [a, rb%node]
         p%node_b = rb%node
         p%w(1:2) = 1.0_dp
         p%n = nrm
         p%t = [nrm(2), -nrm(1)]
         p%g0 = dot_product(coord(:, a) - xb, nrm)
         p%position = xb
      end associate
   end subroutine rigid_pair

   !> The pair of node p%node_a with the edges of surface B (MATCHING
   !! SEGMENT): axes of the nearest edge at a's projection, master nodes,
   !! weights and gap averaged over a's tributary zone.  NODE_UNMATCHED when
   !! a faces no edge of B, NODE_REJECTED (an error reported) when its zone
   !! covers more nodes of B than a pair can hold.
   subroutine segment_pair(m, ie_a, ik_a, ie_b, ik_b, area_a, tol, size_model, file, p, errors, &
                           outcome)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ie_a(:), ik_a(:)        !! edges of surface A
      integer, intent(in) :: ie_b(:), ik_b(:)        !! edges of surface B
      real(dp), intent(in) :: area_a(:)              !! (npoin) lumped areas of surface A [length^2]
      real(dp), intent(in) :: tol, size_model        !! pairing tolerance, model size [length]
      character(len=*), intent(in) :: file
      type(contact_pair_t), intent(inout) :: p       !! node_a, line set; the rest set here
      type(error_list_t), intent(inout) :: errors
      integer, intent(out) :: outcome                !! NODE_PAIRED, NODE_UNMATCHED or NODE_REJECTED
      real(dp) :: xi, xb(2), nrm(2), gavg, mw(MAX_PAIR_NODES - 1)
      integer :: kb, nm, mnodes(MAX_PAIR_NODES - 1), status

      outcome = NODE_UNMATCHED
      call nearest_edge(m, ie_b, ik_b, m%coord(:, p%node_a), tol, kb, xi, xb, nrm)
      if (kb == 0) return
      p%kind = PAIR_SEGMENT
      p%nodes(1) = p%node_a
      p%w(1) = 1.0_dp
      call tributary_weights(m, ie_a, ik_a, ie_b, ik_b, area_a, p%node_a, nrm, tol, size_model, &
                             nm, mnodes, mw, &
                             gavg, status)
      if (status == TRIB_FULL) then
         call errors%add(E_COARSE_SIDE, 'CONTACT: interface '//itoa(p%iface)//': node '// &
                         itoa(p%node_a)// &
                         ' of surface A faces more than '//itoa(MAX_PAIR_NODES - 1)// &
                         ' nodes of surface B; with '// &
                         'MATCHING SEGMENT surface A should be the finer of the two', file=file, &
                         line=p%line)
         outcome = NODE_REJECTED
         return
      end if
      if (status /= TRIB_OK) return
      p%nn = 1 + nm
      p%nodes(2:1 + nm) = mnodes(1:nm)
      p%w(2:1 + nm) = mw(1:nm)
      p%node_b = mnodes(maxloc(mw(1:nm), 1))
      p%n = nrm
      p%t = [nrm(2), -nrm(1)]
      p%g0 = gavg
      p%g_point = dot_product(m%coord(:, p%node_a) - xb, nrm)
      p%position = xb
      outcome = NODE_PAIRED
   end subroutine segment_pair

   !> Side B must face surface A: the outward normals of B at the pairs and
   !! of A at their nodes point against each other (for every kind of pair:
   !! node to node, to the edges of B, to a rigid profile).  False (an error
   !! reported) where they do not.
   logical function facing(m, s, iface, ie_a, ik_a, pairs, file, errors)
      type(model_t), intent(in) :: m
      type(iface_spec_t), intent(in) :: s
      integer, intent(in) :: iface
      integer, intent(in) :: ie_a(:), ik_a(:)        !! edges of surface A
      type(contact_pair_t), intent(in) :: pairs(:)   !! the interface's pairs
      character(len=*), intent(in) :: file
      type(error_list_t), intent(inout) :: errors
      real(dp), allocatable :: normal(:, :)
      character(len=:), allocatable :: list
      integer :: k, nbad

      allocate (normal(2, m%npoin))
      call surface_normals(m, ie_a, ik_a, normal)
      nbad = 0
      list = ''
      do k = 1, size(pairs)
         if (dot_product(pairs(k)%n, normal(:, pairs(k)%node_a)) <= 0.0_dp) cycle
         call note_node(nbad, list, pairs(k)%node_a)
      end do
      facing = nbad == 0
      if (facing) return
      if (nbad > 20) list = list//' ...'
      if (s%law%rigid > 0) then
         call errors%add('E-RIGID', 'CONTACT: interface '//itoa(iface)//': '//itoa(nbad)// &
                         ' node(s) of '// &
                         'surface A lie where the rigid profile faces away from them (its outward &
                         &normal '// &
                         'points the way of surface A''s own):'//list// &
                         '; list the vertices with the rigid '// &
                         'body on their left (anticlockwise around the body)', file=file, &
                         line=s%surf(1)%line)
      else
         call errors%add('E-CONTACT', 'CONTACT: interface '//itoa(iface)//': '//itoa(nbad)// &
                         ' node(s) of '// &
                         'surface A face the back of surface B (both outward normals point the &
                         &same way):'// &
                         list//'; a SURFACE is on the wrong face of its body: A and B must be the &
                         &faces of the '// &
                         'two bodies that look at each other', file=file, line=s%surf(1)%line)
      end if
   end function facing

   !> Count a node for a message and list the first twenty.
   pure subroutine note_node(nbad, list, node)
      integer, intent(inout) :: nbad
      character(len=:), allocatable, intent(inout) :: list
      integer, intent(in) :: node
      nbad = nbad + 1
      if (nbad <= 20) list = list//' '//itoa(node)
   end subroutine note_node
end module contact_pairing
