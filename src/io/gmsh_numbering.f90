!> The model's nodes and elements from the 2-D elements of a parsed `.msh` file.
!!
!! Owns the numbering of the nodes the 2-D elements use (1..npoin in
!! increasing tag order, by a stable merge sort of the tags and a binary
!! search in them, so that time and memory follow the number of nodes and
!! not the size of the tags), the connectivity of the model's elements, and
!! their orientation (clockwise elements reversed so that det J > 0).
!! Duplicate and undefined node tags are reported (E-GMSH, file and line).
module gmsh_numbering
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa
   use model, only: model_t, MAX_NODE
   use gmsh_mesh, only: gmsh_mesh_t, gmsh_nnode
   implicit none
   private

   public :: number_nodes, tag_index, model_node, sort_by_key, signed_area, reverse_element

contains

   !> The nodes and elements of the model: the nodes used by the 2-D elements
   !! surf, numbered 1..npoin in increasing tag order, and the elements with
   !! their corners made anticlockwise.  The tags are sorted (tags, with
   !! model_of(k) the model node of tags(k), 0 for an unused tag), so that
   !! memory and time follow the number of nodes, not the size of the tags.
   !! ok is false if a tag is defined twice or used but not defined (reported).
   subroutine number_nodes(msh, surf, m, tags, model_of, errors, ok)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: surf(:)
      type(model_t), intent(inout) :: m                !! matno set; mesh filled here
      integer, allocatable, intent(out) :: tags(:)     !! the node tags of $Nodes, ascending
      integer, allocatable, intent(out) :: model_of(:) !! model node of tags(k), 0 if unused
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer, allocatable :: perm(:)
      integer :: k, j, ie, nn, ip, nelem, npoin, n

      ok = .false.
      nelem = size(surf)
      n = msh%nnodes
      allocate (perm(n), model_of(n))
      perm = [(k, k=1, n)]
      call sort_by_key(msh%node_tag, perm)
      tags = msh%node_tag(perm)
      do k = 2, n
         if (tags(k) == tags(k - 1)) then
            call errors%add('E-GMSH', 'node tag '//itoa(tags(k))//' appears twice in $Nodes', &
                            file=msh%path, &
                            line=max(msh%node_line(perm(k)), msh%node_line(perm(k - 1))))
            return
         end if
      end do
      model_of = 0
      do ie = 1, nelem
         k = surf(ie)
         do j = 1, gmsh_nnode(msh%etype(k))
            ip = tag_index(tags, msh%enodes(j, k))
            if (ip == 0) then
               call errors%add('E-GMSH', 'element refers to node tag '//itoa(msh%enodes(j, k))// &
                               ', which $Nodes does not define', file=msh%path, line=msh%eline(k))
               return
            end if
            model_of(ip) = 1
         end do
      end do
      npoin = 0
      do k = 1, n
         if (model_of(k) == 0) cycle
         npoin = npoin + 1
         model_of(k) = npoin
      end do
      m%npoin = npoin
      m%nelem = nelem
      if (allocated(m%coord)) deallocate (m%coord)
      if (allocated(m%node_tag)) deallocate (m%node_tag)
      if (allocated(m%node_line)) deallocate (m%node_line)
      if (allocated(m%lnods)) deallocate (m%lnods)
      if (allocated(m%nnode_e)) deallocate (m%nnode_e)
      if (allocated(m%elem_line)) deallocate (m%elem_line)
      allocate (m%coord(2, npoin), m%node_tag(npoin), m%node_line(npoin), &
                m%lnods(MAX_NODE, nelem), m%nnode_e(nelem), m%elem_line(nelem))
      do k = 1, n
         if (model_of(k) == 0) cycle
         m%coord(:, model_of(k)) = msh%xyz(1:2, perm(k))
         m%node_tag(model_of(k)) = tags(k)
         m%node_line(model_of(k)) = msh%node_line(perm(k))
      end do
      m%lnods = 0
      do ie = 1, nelem
         k = surf(ie)
         nn = gmsh_nnode(msh%etype(k))
         m%nnode_e(ie) = nn
         m%elem_line(ie) = msh%eline(k)
         do j = 1, nn
            m%lnods(j, ie) = model_of(tag_index(tags, msh%enodes(j, k)))
         end do
         ! anticlockwise corners: reverse a clockwise element
         if (signed_area(m, ie) < 0.0_dp) call reverse_element(m%lnods(1:nn, ie))
      end do
      m%nnode = maxval(m%nnode_e)
      ok = .true.
   end subroutine number_nodes

   !> Position of tag in the ascending list tags (binary search), 0 if absent.
   pure integer function tag_index(tags, tag) result(k)
      integer, intent(in) :: tags(:)
      integer, intent(in) :: tag
      integer :: lo, hi, mid
      lo = 1
      hi = size(tags)
      k = 0
      do while (lo <= hi)
         mid = lo + (hi - lo)/2
         if (tags(mid) == tag) then
            k = mid
            return
         else if (tags(mid) < tag) then
            lo = mid + 1
         else
            hi = mid - 1
         end if
      end do
   end function tag_index

   !> The model node of a tag (0 for a tag of no used node).
   pure integer function model_node(tags, model_of, tag) result(q)
      integer, intent(in) :: tags(:), model_of(:), tag
      integer :: k
      q = 0
      k = tag_index(tags, tag)
      if (k > 0) q = model_of(k)
   end function model_node

   !> Sort the permutation perm so that key(perm) ascends (a merge sort, stable:
   !! n log n, whatever the keys).
   pure subroutine sort_by_key(key, perm)
      integer, intent(in) :: key(:)
      integer, intent(inout) :: perm(:)
      integer, allocatable :: work(:)
      integer :: width, lo, mid, hi, i, j, k, n
      n = size(perm)
      allocate (work(n))
      width = 1
      do while (width < n)
         lo = 1
         do while (lo <= n)
            mid = min(lo + width - 1, n)
            hi = min(lo + 2*width - 1, n)
            i = lo
            j = mid + 1
            do k = lo, hi
               if (j > hi) then
                  work(k) = perm(i)
                  i = i + 1
               else if (i > mid) then
                  work(k) = perm(j)
                  j = j + 1
               else if (key(perm(j)) < key(perm(i))) then
                  work(k) = perm(j)
                  j = j + 1
               else
                  work(k) = perm(i)
                  i = i + 1
               end if
            end do
            lo = lo + 2*width
         end do
         perm = work
         width = 2*width
      end do
   end subroutine sort_by_key

   !> Shoelace area of the corner polygon (positive when anticlockwise).
   pure real(dp) function signed_area(m, ie) result(a)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ie
      integer :: nc, k, p, q
      nc = merge(3, 4, m%nnode_e(ie) == 3)
      a = 0.0_dp
      do k = 1, nc
         p = m%lnods(k, ie)
         q = m%lnods(mod(k, nc) + 1, ie)
         a = a + m%coord(1, p)*m%coord(2, q) - m%coord(1, q)*m%coord(2, p)
      end do
      a = 0.5_dp*a
   end function signed_area

   !> Clockwise to anticlockwise: corners 1, n, ..., 2, and the midside node
   !! of edge k follows its edge (Q8/Q9: 1 4 3 2 | 8 7 6 5 | 9).
   pure subroutine reverse_element(ln)
      integer, intent(inout) :: ln(:)
      integer :: old(size(ln))
      old = ln
      select case (size(ln))
      case (3)
         ln = old([1, 3, 2])
      case (4)
         ln = old([1, 4, 3, 2])
      case (8)
         ln = old([1, 4, 3, 2, 8, 7, 6, 5])
      case (9)
         ln = old([1, 4, 3, 2, 8, 7, 6, 5, 9])
      end select
   end subroutine reverse_element

end module gmsh_numbering
