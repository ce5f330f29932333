!> Element topology: the corners and edges of the 2-D elements.
!!
!! Elements by node count: 3 (linear triangle), 4 (bilinear quadrilateral),
!! 8 (serendipity quadrilateral) and 9 (Lagrange quadrilateral).  Node order:
!! corners anticlockwise, then the midside nodes of edges 1-2, 2-3, 3-4, 4-1,
!! then the centre node (the gmsh/VTK order).  Edge k runs from corner k to
!! corner k+1 (cyclic) with midside node `ncorn + k`; an edge's node list is
!! (start, end, mid).  For a positively oriented element the element lies to
!! the left of the walk start -> end.
!!
!! This is numbering only, no geometry: the readers and the contact surfaces
!! need it without the element kernels, which take it from here (shape_2d
!! re-exports it).  docs/elements.md draws the numbering.
!!
!! Ref: Hinton & Owen, *Finite Element Programming* (1977), routine SFR2
!!      (node numbering of the element family).
module topology
   implicit none
   private

   public :: corner_count, nedges, element_edge_nodes

contains

   !> Number of corner nodes (3 or 4); 0 if the element is not supported.
   pure integer function corner_count(nnode)
      integer, intent(in) :: nnode   !! nodes per element

      select case (nnode)
      case (3)
         corner_count = 3
      case (4, 8, 9)
         corner_count = 4
      case default
         corner_count = 0
      end select
   end function corner_count

   !> Number of edges (3 or 4); 0 if the element is not supported.
   pure integer function nedges(nnode)
      integer, intent(in) :: nnode   !! nodes per element

      nedges = corner_count(nnode)
   end function nedges

   !> Local node numbers of edge `iedge`, in the order (start, end, mid).
   !!
   !! Edge k runs from corner k to corner k+1 (cyclic); quadratic elements
   !! add midside node 4+k.  An invalid element or edge gives `nn = 0`.
   pure subroutine element_edge_nodes(nnode, iedge, local, nn)
      integer, intent(in) :: nnode      !! nodes per element: 3, 4, 8 or 9
      integer, intent(in) :: iedge      !! edge number, 1..nedges(nnode)
      integer, intent(out) :: local(3)  !! local node numbers; local(3) = 0 for 2-node edges
      integer, intent(out) :: nn        !! nodes on the edge: 2, 3, or 0 if invalid
      integer :: ncorn

      local = 0
      nn = 0
      ncorn = corner_count(nnode)
      if (ncorn == 0 .or. iedge < 1 .or. iedge > ncorn) return
      local(1) = iedge
      local(2) = mod(iedge, ncorn) + 1
      if (nnode >= 8) then
         local(3) = ncorn + iedge
         nn = 3
      else
         nn = 2
      end if
   end subroutine element_edge_nodes
end module topology
