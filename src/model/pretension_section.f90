!> Build the pretension sections of a model (after reading, before the
!! contact definition): the section's nodes duplicated, the elements on the
!! +axis side relinked to the copies, the copies tied to the originals
!! across the axis, one reference node per section, free along the axis only
!! and loaded by -F (tension F across the section; module pretension).
!! Errors are reported at the card's line (code E-PRETENSION).
module pretension_section
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa
   use model, only: model_t, restraint_t, point_load_t, MAX_NODE
   use pretension, only: pretension_t
   implicit none
   private
   public :: define_pretensions, is_pretension_reference, pretension_links

contains

   !> Every section of m%pretensions; the model grows by the copies and the
   !! reference nodes.
   subroutine define_pretensions(m, errors)
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: errors
      integer :: k, n0
      if (.not. allocated(m%pretensions)) allocate (m%pretensions(0))
      do k = 1, size(m%pretensions)
         n0 = errors%n
         call check_section(m, m%pretensions(k), errors)
         if (errors%n > n0) cycle
         call build_section(m, m%pretensions(k))
      end do
   end subroutine define_pretensions

   !> The section's nodes on one line across the axis, each with elements on
   !! both sides of it, none restrained along the axis, none in another section.
   subroutine check_section(m, p, errors)
      type(model_t), intent(in) :: m
      type(pretension_t), intent(inout) :: p
      type(error_list_t), intent(inout) :: errors
      integer :: i, ip, ie, k, nn, ax
      real(dp) :: tol, c
      logical, allocatable :: plus(:), minus(:)
      integer, allocatable :: pe(:), me(:)

      ax = p%axis
      tol = 1.0e-9_dp*max(maxval(abs(m%coord)), tiny(1.0_dp))
      p%cut = m%coord(ax, p%nodes(1))
      do i = 2, size(p%nodes)
         if (abs(m%coord(ax, p%nodes(i)) - p%cut) > tol) then
            call err('node '//itoa(p%nodes(i))//' lies at '//trim(merge('x', 'y', ax == 1))// &
                     ' = '// &
                     rtoa(m%coord(ax, p%nodes(i)))//', off the cut '// &
                     trim(merge('x', 'y', ax == 1))//' = '// &
                     rtoa(p%cut)//' of node '//itoa(p%nodes(1))// &
                     ' (a section is a straight cut across the axis)')
            return
         end if
      end do
      do k = 1, size(m%fixes)
         if (.not. any(p%nodes == m%fixes(k)%node)) cycle
         if (m%fixes(k)%fixed(ax)) then
            call err('node '//itoa(m%fixes(k)%node)// &
                     ' of the section is restrained along the axis (RESTRAINTS, '// &
                     'line '//itoa(m%fixes(k)%line)//'): the section must be free to open')
            return
         end if
      end do
      do k = 1, size(m%pretensions)
         if (m%pretensions(k)%line == p%line .or. .not. allocated(m%pretensions(k)%copies)) cycle
         if (any([(any(m%pretensions(k)%nodes == p%nodes(i)), i=1, size(p%nodes))])) then
            call err('the section shares nodes with section "'//m%pretensions(k)%name// &
                     '" (line '// &
                     itoa(m%pretensions(k)%line)//')')
            return
         end if
      end do
      allocate (plus(size(p%nodes)), minus(size(p%nodes)), pe(0), me(0))
      plus = .false.
      minus = .false.
      do ie = 1, m%nelem
         nn = m%nnode_e(ie)
         if (.not. any([(any(p%nodes == m%lnods(k, ie)), k=1, nn)])) cycle
         c = sum(m%coord(ax, m%lnods(1:nn, ie)))/nn
         do k = 1, nn
            do i = 1, size(p%nodes)
               if (m%lnods(k, ie) /= p%nodes(i)) cycle
               if (c > p%cut) plus(i) = .true.
               if (c < p%cut) minus(i) = .true.
            end do
         end do
         if (c > p%cut) then
            pe = [pe, ie]
         else
            me = [me, ie]
         end if
      end do
      do i = 1, size(p%nodes)
         ip = p%nodes(i)
         if (.not. (plus(i) .and. minus(i))) then
            call err('node '//itoa(ip)//' has elements on '// &
                     trim(merge('the -axis side only', 'the +axis side only', &
                     minus(i)))//trim(merge(' (no element at all)', '                    ', &
                                            .not. (plus(i) .or. &
                     minus(i))))//': a section cuts through a body, every node between elements on &
                     &both sides')
            return
         end if
      end do
      p%plus_elems = pe
      p%minus_elems = me
   contains
      subroutine err(msg)
         character(len=*), intent(in) :: msg
         call errors%add('E-PRETENSION', 'LOADS/PRETENSION: section "'//p%name//'": '//msg, &
                         file=m%deck_file, &
                         line=p%line, col=11)
      end subroutine err
   end subroutine check_section

   !> Copies, relinking, ties, reference node and its load.
   subroutine build_section(m, p)
      type(model_t), intent(inout) :: m
      type(pretension_t), intent(inout) :: p
      integer :: i, k, ie, np, ns, ax, tr, nt
      integer, allocatable :: ties(:, :)
      logical :: fixed_t
      type(restraint_t), allocatable :: addfix(:)

      ax = p%axis
      tr = 3 - ax
      np = m%npoin
      ns = size(p%nodes)
      p%copies = [(np + i, i=1, ns)]
      p%ref = np + ns + 1
      ! nodes: the copies at the originals, the reference node at the middle of the section
      m%coord = reshape([m%coord, m%coord(:, p%nodes), &
                         0.5_dp*(minval(m%coord(:, p%nodes), dim=2) + &
                                 maxval(m%coord(:, p%nodes), dim=2))], &
                        [2, np + ns + 1])
      m%coord(ax, p%ref) = p%cut
      m%node_line = [m%node_line, (p%line, i=1, ns + 1)]
      if (allocated(m%node_tag)) m%node_tag = [m%node_tag, (0, i=1, ns + 1)]
      m%npoin = np + ns + 1
      ! the +axis side's elements take the copies
      do k = 1, size(p%plus_elems)
         ie = p%plus_elems(k)
         do i = 1, m%nnode_e(ie)
            do nt = 1, ns
               if (m%lnods(i, ie) == p%nodes(nt)) m%lnods(i, ie) = p%copies(nt)
            end do
         end do
      end do
      ! across the axis: the copy shares the original's displacement (a tie), or its restraint
      allocate (ties(3, 0), addfix(0))
      do i = 1, ns
         fixed_t = .false.
         do k = 1, size(m%fixes)
            if (m%fixes(k)%node /= p%nodes(i) .or. .not. m%fixes(k)%fixed(tr)) cycle
            fixed_t = .true.
            addfix = [addfix, restraint_t(node=p%copies(i), &
                                          fixed=merge([.true., .false.], [.false., .true.], &
                                                      tr == 1), &
                                          value=m%fixes(k)%value*merge([1.0_dp, 0.0_dp], &
                                                                       [0.0_dp, 1.0_dp], tr == 1), &
                                          icase=m%fixes(k)%icase, line=m%fixes(k)%line)]
            exit
         end do
         if (.not. fixed_t) then
            ties = reshape([ties, p%nodes(i), p%copies(i), tr], [3, size(ties, 2) + 1])
         end if
      end do
      ! the reference node moves along the axis only, loaded by -F (tension F across the cut)
      addfix = [addfix, restraint_t(node=p%ref, fixed=merge([.true., .false.], [.false., .true.], &
                                                            tr == 1), &
                                    line=p%line)]
      m%fixes = [m%fixes, addfix]
      m%ties = reshape([m%ties, ties], [3, size(m%ties, 2) + size(ties, 2)])
      block
         type(point_load_t) :: pl
         pl%node = p%ref
         pl%force = 0.0_dp
         pl%force(ax) = -p%force
         pl%icase = p%icase
         pl%line = p%line
         m%point_loads = [m%point_loads, pl]
      end block
   end subroutine build_section

   !> Is node ip the reference node of a pretension section?
   pure logical function is_pretension_reference(m, ip)
      type(model_t), intent(in) :: m
      integer, intent(in) :: ip
      integer :: k
      is_pretension_reference = .false.
      if (.not. allocated(m%pretensions)) return
      do k = 1, size(m%pretensions)
         if (m%pretensions(k)%ref == ip) is_pretension_reference = .true.
      end do
   end function is_pretension_reference

   !> Node couplings of the sections' springs (copy, original, reference
   !! node), for the equation graph and the rigid-body check.
   pure subroutine pretension_links(m, links)
      type(model_t), intent(in) :: m
      integer, allocatable, intent(out) :: links(:, :)   !! (2, nlink)
      integer :: k, i, n
      n = 0
      if (allocated(m%pretensions)) then
         do k = 1, size(m%pretensions)
            if (allocated(m%pretensions(k)%copies)) n = n + 3*size(m%pretensions(k)%nodes)
         end do
      end if
      allocate (links(2, n))
      n = 0
      if (.not. allocated(m%pretensions)) return
      do k = 1, size(m%pretensions)
         if (.not. allocated(m%pretensions(k)%copies)) cycle
         associate (p => m%pretensions(k))
            do i = 1, size(p%nodes)
               links(:, n + 1) = [p%copies(i), p%nodes(i)]
               links(:, n + 2) = [p%copies(i), p%ref]
               links(:, n + 3) = [p%nodes(i), p%ref]
               n = n + 3
            end do
         end associate
      end do
   end subroutine pretension_links
end module pretension_section
