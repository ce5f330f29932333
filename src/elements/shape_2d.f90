!> Shape functions of the 2-D solid elements and of their edges.
!!
!! Elements by node count: 3 (linear triangle, code 303), 4 (bilinear
!! quadrilateral, 404), 8 (serendipity quadrilateral, 408) and 9 (Lagrange
!! quadrilateral, 409).  Node order: corners anticlockwise, then the midside
!! nodes of edges 1-2, 2-3, 3-4, 4-1, then the centre node (the gmsh/VTK
!! order).  Quadrilateral corners sit at (s,t) = (-1,-1), (1,-1), (1,1),
!! (-1,1); triangle corners at (0,0), (1,0), (0,1).
!!
!! Edge k runs from corner k to corner k+1 (cyclic) with midside node
!! `ncorn + k`; an edge's node list is (start, end, mid).  For a positively
!! oriented element the element lies to the left of the walk start -> end.
!! That numbering (`corner_count`, `nedges`, `element_edge_nodes`) lives in
!! the model layer (module topology), which the readers use without the
!! kernels; it is re-exported here.
!!
!! Procedures that receive an unsupported `nnode` or `nn` stop with an
!! internal error: callers validate element types with `element_code`
!! (0 = unsupported) before they get here.
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routine SFR2;
!!      Zienkiewicz & Taylor, *The Finite Element Method*, vol. 1
!!      (serendipity and Lagrange families).
module shape_2d
   use kinds, only: dp
   use topology, only: corner_count, nedges, element_edge_nodes   ! numbering, re-exported
   implicit none
   private

   public :: shape_functions, edge_shape, element_edge_nodes, nedges, corner_count, &
             element_code, element_nnode, node_natural_coords

   !> Natural coordinates of the nine nodes of the quadrilateral family.
   real(dp), parameter :: quad_nodes(2, 9) = reshape([ &
                          -1.0_dp, -1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, 1.0_dp, -1.0_dp, 1.0_dp, &
                          0.0_dp, -1.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp, -1.0_dp, 0.0_dp, &
                          0.0_dp, 0.0_dp], [2, 9])

contains

   !> Element type code (303, 404, 408, 409) of an element with `nnode`
   !! nodes; 0 if the element is not supported.
   pure integer function element_code(nnode)
      integer, intent(in) :: nnode   !! nodes per element

      select case (nnode)
      case (3)
         element_code = 303
      case (4)
         element_code = 404
      case (8)
         element_code = 408
      case (9)
         element_code = 409
      case default
         element_code = 0
      end select
   end function element_code

   !> Node count of an element type code (303, 404, 408, 409); 0 if unknown.
   pure integer function element_nnode(code)
      integer, intent(in) :: code   !! element type code

      select case (code)
      case (303)
         element_nnode = 3
      case (404)
         element_nnode = 4
      case (408)
         element_nnode = 8
      case (409)
         element_nnode = 9
      case default
         element_nnode = 0
      end select
   end function element_nnode

   !> Natural coordinates (s, t) of the element's nodes.
   pure subroutine node_natural_coords(nnode, snode)
      integer, intent(in) :: nnode             !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(out) :: snode(2, nnode) !! (s, t) of each node

      select case (nnode)
      case (3)
         snode = reshape([0.0_dp, 0.0_dp, 1.0_dp, 0.0_dp, 0.0_dp, 1.0_dp], [2, 3])
      case (4, 8, 9)
         snode = quad_nodes(:, 1:nnode)
      case default
         error stop 'shape_2d: node_natural_coords: unsupported nnode (internal error)'
      end select
   end subroutine node_natural_coords

   !> Shape functions and their natural derivatives at (s, t) (SFR2).
   !!
   !! T3: N = (1-s-t, s, t).  Q4: N_i = (1+s s_i)(1+t t_i)/4.
   !! Q8 (serendipity): corners N_i = (1+s s_i)(1+t t_i)(s s_i + t t_i - 1)/4,
   !! midsides (1-s²)(1+t t_i)/2 or (1+s s_i)(1-t²)/2.
   !! Q9 (Lagrange): products of the 1-D quadratic Lagrange polynomials.
   !!
   !! Ref: Hinton & Owen (1977), SFR2; Zienkiewicz & Taylor, vol. 1
   !!      (serendipity and Lagrange shape functions).
   pure subroutine shape_functions(nnode, s, t, shape, deriv)
      integer, intent(in) :: nnode             !! nodes per element: 3, 4, 8 or 9
      real(dp), intent(in) :: s                !! first natural coordinate
      real(dp), intent(in) :: t                !! second natural coordinate
      real(dp), intent(out) :: shape(nnode)    !! N_i(s, t)
      real(dp), intent(out) :: deriv(2, nnode) !! dN_i/ds (row 1) and dN_i/dt (row 2)
      real(dp) :: si, ti, ls(3), lt(3), dls(3), dlt(3)
      integer :: i, ix(9), iy(9)

      select case (nnode)
      case (3)
         shape = [1.0_dp - s - t, s, t]
         deriv(1, :) = [-1.0_dp, 1.0_dp, 0.0_dp]
         deriv(2, :) = [-1.0_dp, 0.0_dp, 1.0_dp]

      case (4)
         do i = 1, 4
            si = quad_nodes(1, i)
            ti = quad_nodes(2, i)
            shape(i) = 0.25_dp*(1.0_dp + s*si)*(1.0_dp + t*ti)
            deriv(1, i) = 0.25_dp*si*(1.0_dp + t*ti)
            deriv(2, i) = 0.25_dp*ti*(1.0_dp + s*si)
         end do

      case (8)
         do i = 1, 4
            si = quad_nodes(1, i)
            ti = quad_nodes(2, i)
            shape(i) = 0.25_dp*(1.0_dp + s*si)*(1.0_dp + t*ti)*(s*si + t*ti - 1.0_dp)
            deriv(1, i) = 0.25_dp*si*(1.0_dp + t*ti)*(2.0_dp*s*si + t*ti)
            deriv(2, i) = 0.25_dp*ti*(1.0_dp + s*si)*(s*si + 2.0_dp*t*ti)
         end do
         do i = 5, 8
            si = quad_nodes(1, i)
            ti = quad_nodes(2, i)
            if (abs(si) < 0.5_dp) then   ! s_i = 0: node on an edge t = +-1
               shape(i) = 0.5_dp*(1.0_dp - s*s)*(1.0_dp + t*ti)
               deriv(1, i) = -s*(1.0_dp + t*ti)
               deriv(2, i) = 0.5_dp*ti*(1.0_dp - s*s)
            else
               shape(i) = 0.5_dp*(1.0_dp + s*si)*(1.0_dp - t*t)
               deriv(1, i) = 0.5_dp*si*(1.0_dp - t*t)
               deriv(2, i) = -t*(1.0_dp + s*si)
            end if
         end do

      case (9)
         ! 1-D Lagrange polynomials at -1, 0, +1 (index 1, 2, 3)
         call lagrange3(s, ls, dls)
         call lagrange3(t, lt, dlt)
         ix = nint(quad_nodes(1, :)) + 2
         iy = nint(quad_nodes(2, :)) + 2
         do i = 1, 9
            shape(i) = ls(ix(i))*lt(iy(i))
            deriv(1, i) = dls(ix(i))*lt(iy(i))
            deriv(2, i) = ls(ix(i))*dlt(iy(i))
         end do

      case default
         error stop 'shape_2d: shape_functions: unsupported nnode (internal error)'
      end select
   end subroutine shape_functions

   !> Shape functions of a 2- or 3-node edge, nodes in (start, end, mid)
   !! order, at the edge coordinate s in [-1, 1] (start at -1, end at +1,
   !! midside node at 0).
   !!
   !! Ref: Hinton & Owen (1977), SFR2 (1-D case); Zienkiewicz & Taylor, vol. 1
   !!      (one-dimensional Lagrange shape functions).
   pure subroutine edge_shape(nn, s, shape, deriv)
      integer, intent(in) :: nn            !! nodes on the edge: 2 or 3
      real(dp), intent(in) :: s            !! edge coordinate
      real(dp), intent(out) :: shape(nn)   !! G_i(s)
      real(dp), intent(out) :: deriv(nn)   !! dG_i/ds
      real(dp) :: l(3), dl(3)

      select case (nn)
      case (2)
         shape = [0.5_dp*(1.0_dp - s), 0.5_dp*(1.0_dp + s)]
         deriv = [-0.5_dp, 0.5_dp]
      case (3)
         call lagrange3(s, l, dl)
         shape = [l(1), l(3), l(2)]
         deriv = [dl(1), dl(3), dl(2)]
      case default
         error stop 'shape_2d: edge_shape: unsupported nn (internal error)'
      end select
   end subroutine edge_shape

   !> Quadratic Lagrange polynomials through -1, 0, +1 and their derivatives.
   pure subroutine lagrange3(x, l, dl)
      real(dp), intent(in) :: x        !! coordinate in [-1, 1]
      real(dp), intent(out) :: l(3)    !! values at x of the polynomials of -1, 0, +1
      real(dp), intent(out) :: dl(3)   !! derivatives

      l = [0.5_dp*x*(x - 1.0_dp), 1.0_dp - x*x, 0.5_dp*x*(x + 1.0_dp)]
      dl = [x - 0.5_dp, -2.0_dp*x, x + 0.5_dp]
   end subroutine lagrange3

end module shape_2d
