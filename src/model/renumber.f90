!> Bandwidth and profile reduction of the node graph: reverse Cuthill-McKee
!! (RCM) started from a pseudo-peripheral node (George & Liu).
!!
!! The result is an *order*: `order(k)` is the node that comes k-th, which is
!! what `build_dof_map` takes to number the equations.  The user's node
!! numbers never change; only the equation numbers do.
!!
!! Cuthill-McKee visits the graph breadth first from a start node, taking the
!! unvisited neighbours of each node by increasing degree; reversing that
!! order gives a profile never larger, and usually much smaller, than the
!! forward one (Liu & Sherman 1976).  Starting at a node of maximal
!! eccentricity gives long, narrow level structures, i.e. a small bandwidth:
!! George & Liu's pseudo-peripheral node finder approximates one in a few
!! breadth-first sweeps.  Every connected component (bodies in contact are
!! separate components until the contact pairs link them; nodes of no
!! element are components of their own) is numbered in turn.
!!
!! Ref: E. Cuthill, J. McKee, "Reducing the bandwidth of sparse symmetric
!!      matrices", Proc. 24th ACM Nat. Conf. (1969) 157-172;
!!      A. George, J. W. H. Liu, *Computer Solution of Large Sparse Positive
!!      Definite Systems*, Prentice-Hall (1981), sec. 4.3 (RCM, FNROOT, ROOTLS);
!!      W.-H. Liu, A. H. Sherman, SIAM J. Numer. Anal. 13 (1976) 198-213.
module renumber
   implicit none
   private
   public :: rcm_order, is_permutation, RENUMBER_AUTO, RENUMBER_RCM, RENUMBER_NONE

   !> Renumbering choices of the deck (OPTIONS RENUMBER).
   character(len=*), parameter :: RENUMBER_AUTO = 'AUTO'   !! RCM for the skyline
                                                           !! solver, none otherwise
   character(len=*), parameter :: RENUMBER_RCM = 'RCM'
   character(len=*), parameter :: RENUMBER_NONE = 'NONE'

contains

   !> Reverse Cuthill-McKee order of a graph given in CSR form.
   !!
   !! Self-loops (a node listed in its own adjacency, as `build_node_graph`
   !! does) are ignored.  O(n + nnz + sum of neighbour sorts) work.
   pure subroutine rcm_order(n, xadj, adjncy, order)
      integer, intent(in) :: n             !! number of nodes
      integer, intent(in) :: xadj(:)       !! (n+1) 1-based CSR pointers
      integer, intent(in) :: adjncy(:)     !! neighbours of each node
      integer, intent(out) :: order(:)     !! (n) node numbered k-th, reverse Cuthill-McKee
      integer, allocatable :: deg(:), ls(:), xls(:)
      logical, allocatable :: placed(:), mask(:), seen(:)
      integer :: i, root, nlvl, nnum, first, last, k, node, j, nb, nnew, ccsize

      allocate (deg(n), placed(n), mask(n), ls(n), xls(n + 1), seen(n))
      seen = .false.
      do i = 1, n
         deg(i) = 0
         do j = xadj(i), xadj(i + 1) - 1
            if (adjncy(j) /= i) deg(i) = deg(i) + 1
         end do
      end do
      placed = .false.
      mask = .true.
      nnum = 0
      do i = 1, n
         if (placed(i)) cycle
         ! one connected component, from a pseudo-peripheral node
         root = i
         call pseudo_peripheral(root, xadj, adjncy, deg, mask, seen, ls, xls, nlvl, ccsize)
         ! Cuthill-McKee sweep: breadth first, neighbours by increasing degree
         first = nnum + 1
         nnum = nnum + 1
         order(nnum) = root
         placed(root) = .true.
         k = first
         do while (k <= nnum)
            node = order(k)
            last = nnum
            do j = xadj(node), xadj(node + 1) - 1
               nb = adjncy(j)
               if (nb == node .or. placed(nb)) cycle
               nnum = nnum + 1
               order(nnum) = nb
               placed(nb) = .true.
            end do
            nnew = nnum - last
            if (nnew > 1) call sort_by_degree(order(last + 1:nnum), deg)
            k = k + 1
         end do
         ! nodes of this component no longer take part in later searches
         do k = first, nnum
            mask(order(k)) = .false.
         end do
         ! reverse the component's part of the order
         order(first:nnum) = order(nnum:first:-1)
      end do
   end subroutine rcm_order

   !> George & Liu's pseudo-peripheral node finder (FNROOT).
   !!
   !! From `root`, build the rooted level structure; take a node of minimum
   !! degree in the last level and repeat while the number of levels grows.
   pure subroutine pseudo_peripheral(root, xadj, adjncy, deg, mask, seen, ls, xls, nlvl, ccsize)
      integer, intent(inout) :: root            !! start node in, pseudo-peripheral node out
      integer, intent(in) :: xadj(:), adjncy(:), deg(:)
      logical, intent(in) :: mask(:)            !! nodes still to be numbered
      logical, intent(inout) :: seen(:)         !! work, all false on entry and exit
      integer, intent(inout) :: ls(:), xls(:)   !! level structure (work)
      integer, intent(out) :: nlvl, ccsize      !! levels and size of the component
      integer :: nlvl_new, j, node, mindeg, cand

      call level_structure(root, xadj, adjncy, mask, seen, ls, xls, nlvl, ccsize)
      if (ccsize <= 1 .or. nlvl == ccsize) return
      do
         ! node of minimum degree in the last level
         mindeg = huge(1)
         cand = root
         do j = xls(nlvl), xls(nlvl + 1) - 1
            node = ls(j)
            if (deg(node) < mindeg) then
               mindeg = deg(node)
               cand = node
            end if
         end do
         call level_structure(cand, xadj, adjncy, mask, seen, ls, xls, nlvl_new, ccsize)
         if (nlvl_new <= nlvl) return   ! no gain: keep the previous root
         root = cand
         nlvl = nlvl_new
         if (nlvl == ccsize) return
      end do
   end subroutine pseudo_peripheral

   !> Rooted level structure of the component of `root` among masked nodes (ROOTLS).
   pure subroutine level_structure(root, xadj, adjncy, mask, seen, ls, xls, nlvl, ccsize)
      integer, intent(in) :: root, xadj(:), adjncy(:)
      logical, intent(in) :: mask(:)
      logical, intent(inout) :: seen(:)    !! work, all false on entry and exit
      integer, intent(inout) :: ls(:)      !! nodes level by level
      integer, intent(inout) :: xls(:)     !! start of each level in ls (nlvl+1 used)
      integer, intent(out) :: nlvl, ccsize
      integer :: lbegin, lend, k, node, j, nb

      ls(1) = root
      seen(root) = .true.
      ccsize = 1
      nlvl = 0
      lbegin = 1
      lend = 1
      do
         nlvl = nlvl + 1
         xls(nlvl) = lbegin
         do k = lbegin, lend
            node = ls(k)
            do j = xadj(node), xadj(node + 1) - 1
               nb = adjncy(j)
               if (seen(nb) .or. .not. mask(nb)) cycle
               seen(nb) = .true.
               ccsize = ccsize + 1
               ls(ccsize) = nb
            end do
         end do
         if (ccsize == lend) exit
         lbegin = lend + 1
         lend = ccsize
      end do
      xls(nlvl + 1) = lend + 1
      do k = 1, ccsize
         seen(ls(k)) = .false.
      end do
   end subroutine level_structure

   !> Insertion sort of a short list of nodes by increasing degree (stable).
   pure subroutine sort_by_degree(a, deg)
      integer, intent(inout) :: a(:)
      integer, intent(in) :: deg(:)
      integer :: i, j, v
      do i = 2, size(a)
         v = a(i)
         j = i - 1
         do while (j >= 1)
            if (deg(a(j)) <= deg(v)) exit
            a(j + 1) = a(j)
            j = j - 1
         end do
         a(j + 1) = v
      end do
   end subroutine sort_by_degree

   !> True when `order` holds every number 1..n exactly once.
   pure logical function is_permutation(order, n)
      integer, intent(in) :: order(:)
      integer, intent(in) :: n
      logical :: hit(n)
      integer :: k
      is_permutation = .false.
      if (size(order) /= n) return
      hit = .false.
      do k = 1, n
         if (order(k) < 1 .or. order(k) > n) return
         if (hit(order(k))) return
         hit(order(k)) = .true.
      end do
      is_permutation = .true.
   end function is_permutation
end module renumber
