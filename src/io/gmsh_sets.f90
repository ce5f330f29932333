!> The named node and edge sets of the model from the physical curves and points of a `.msh` file.
!!
!! Owns the sets a MESH block gives the deck's GROUP cards: every physical
!! curve becomes a node set and an edge set (each of its line elements
!! located as an edge of a 2-D element, through the elements of every node),
!! every physical point a node set.  A line element on no element edge, or
!! of another order than the surfaces, is reported (E-GMSH, file and line).
module gmsh_sets
   use errors, only: error_list_t
   use strings, only: itoa
   use model, only: model_t, node_set_t, edge_set_t
   use topology, only: element_edge_nodes, nedges
   use gmsh_mesh, only: gmsh_mesh_t, gmsh_dim, gmsh_nnode
   use gmsh_numbering, only: model_node
   implicit none
   private

   public :: node_elements, build_sets, find_edge, add_sets

contains

   !> The elements of every node, in compressed rows: those of node ip are
   !! elist(eptr(ip):eptr(ip+1)-1).
   pure subroutine node_elements(m, eptr, elist)
      type(model_t), intent(in) :: m
      integer, allocatable, intent(out) :: eptr(:)     !! (npoin + 1)
      integer, allocatable, intent(out) :: elist(:)
      integer :: cnt(m%npoin + 1), ie, j, ip
      cnt = 0
      do ie = 1, m%nelem
         do j = 1, m%nnode_e(ie)
            cnt(m%lnods(j, ie)) = cnt(m%lnods(j, ie)) + 1
         end do
      end do
      allocate (eptr(m%npoin + 1))
      eptr(1) = 1
      do ip = 1, m%npoin
         eptr(ip + 1) = eptr(ip) + cnt(ip)
      end do
      allocate (elist(eptr(m%npoin + 1) - 1))
      cnt = 0
      do ie = 1, m%nelem
         do j = 1, m%nnode_e(ie)
            ip = m%lnods(j, ie)
            elist(eptr(ip) + cnt(ip)) = ie
            cnt(ip) = cnt(ip) + 1
         end do
      end do
   end subroutine node_elements

   !> Node set (and for a curve the edge set) of physical group g: its
   !! elements' nodes, and each of its line elements located as an edge of a
   !! 2-D element (sorted: model node of each tag; eptr/elist: node_elements).
   subroutine build_sets(msh, g, tags, model_of, eptr, elist, m, errors)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: g
      integer, intent(in) :: tags(:), model_of(:)    !! the sorted node tags and their model nodes
      integer, intent(in) :: eptr(:), elist(:)
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: errors
      integer, allocatable :: sel(:), sed(:)
      integer :: nsel
      logical :: inset(m%npoin)
      integer :: k, j, q, tag, iedge, nloc, ie2, mid
      associate (grp => msh%groups(g))
         allocate (sel(msh%nelems), sed(msh%nelems))
         nsel = 0
         inset = .false.
         do k = 1, msh%nelems
            if (gmsh_dim(msh%etype(k)) /= grp%dim) cycle
            if (.not. any(msh%ephys(1:msh%nphys(k), k) == grp%tag)) cycle
            do j = 1, gmsh_nnode(msh%etype(k))
               tag = msh%enodes(j, k)
               q = model_node(tags, model_of, tag)
               if (q == 0) then
                  call errors%add('E-GMSH', 'physical group "'//grp%name//'": node tag '// &
                                  itoa(tag)//' belongs to no 2-D element of the mesh', &
                                  file=msh%path, line=msh%eline(k))
                  return
               end if
               inset(q) = .true.
            end do
            if (grp%dim /= 1) cycle
            ! locate the line element as an edge of a 2-D element
            mid = 0
            if (msh%etype(k) == 8) mid = model_node(tags, model_of, msh%enodes(3, k))
            call find_edge(m, eptr, elist, model_node(tags, model_of, msh%enodes(1, k)), &
                           model_node(tags, model_of, msh%enodes(2, k)), mid, ie2, iedge, nloc)
            if (ie2 < 0) then
               call errors%add('E-GMSH', 'physical curve "'//grp%name//'": a '// &
                               itoa(gmsh_nnode(msh%etype(k)))//'-node line lies on a '// &
                               itoa(nloc)//'-node element edge (mesh the curves with the '// &
                               'same order as the surfaces)', file=msh%path, line=msh%eline(k))
               return
            else if (ie2 == 0) then
               call errors%add('E-GMSH', 'physical curve "'//grp%name// &
                               '": line element is not an edge of any 2-D element', file=msh%path, &
                               line=msh%eline(k))
               return
            end if
            nsel = nsel + 1
            sel(nsel) = ie2
            sed(nsel) = iedge
         end do
         call add_sets(m, grp%name, pack([(q, q=1, m%npoin)], inset), grp%dim == 1, sel(1:nsel), &
                       sed(1:nsel))
      end associate
   end subroutine build_sets

   !> The edge of a 2-D element with end nodes c1, c2 (either way round) and,
   !! if mid > 0, midside node mid; the candidates are the elements of c1.
   !! ie = 0 if there is none; ie = -1 if the first edge with those ends has
   !! the other order (linear against quadratic; nloc its node count).
   pure subroutine find_edge(m, eptr, elist, c1, c2, mid, ie, iedge, nloc)
      type(model_t), intent(in) :: m
      integer, intent(in) :: eptr(:), elist(:)      !! elements of every node (node_elements)
      integer, intent(in) :: c1, c2, mid            !! end nodes, midside node (0: a 2-node line)
      integer, intent(out) :: ie, iedge, nloc
      integer :: e, ie2, loc(3)
      ie = 0
      iedge = 0
      nloc = 0
      do e = eptr(c1), eptr(c1 + 1) - 1
         ie2 = elist(e)
         do iedge = 1, nedges(m%nnode_e(ie2))
            call element_edge_nodes(m%nnode_e(ie2), iedge, loc, nloc)
            associate (ga => m%lnods(loc(1), ie2), gb => m%lnods(loc(2), ie2))
               if (.not. ((ga == c1 .and. gb == c2) .or. (ga == c2 .and. gb == c1))) cycle
            end associate
            if ((nloc == 3) .neqv. (mid /= 0)) then
               ie = -1
               return
            end if
            if (nloc == 3) then
               if (m%lnods(loc(3), ie2) /= mid) cycle
            end if
            ie = ie2
            return
         end do
      end do
   end subroutine find_edge

   !> Append a node set (and, for a curve, an edge set) called `name`.
   subroutine add_sets(m, name, nodes, curve, ielem, iedge)
      type(model_t), intent(inout) :: m
      character(len=*), intent(in) :: name
      integer, intent(in) :: nodes(:)
      logical, intent(in) :: curve                 !! a physical curve: its edges too
      integer, intent(in) :: ielem(:), iedge(:)    !! the curve's edges
      type(node_set_t), allocatable :: tn(:)
      type(edge_set_t), allocatable :: te(:)
      integer :: i
      ! (component by component: gfortran 12 loses deferred-length
      ! character components in array constructors of derived types)
      allocate (tn(size(m%node_sets) + 1))
      do i = 1, size(m%node_sets)
         tn(i)%name = m%node_sets(i)%name
         tn(i)%nodes = m%node_sets(i)%nodes
      end do
      tn(size(tn))%name = name
      tn(size(tn))%nodes = nodes
      call move_alloc(tn, m%node_sets)
      if (.not. curve) return
      allocate (te(size(m%edge_sets) + 1))
      do i = 1, size(m%edge_sets)
         te(i)%name = m%edge_sets(i)%name
         te(i)%ielem = m%edge_sets(i)%ielem
         te(i)%iedge = m%edge_sets(i)%iedge
      end do
      te(size(te))%name = name
      te(size(te))%ielem = ielem
      te(size(te))%iedge = iedge
      call move_alloc(te, m%edge_sets)
   end subroutine add_sets

end module gmsh_sets
