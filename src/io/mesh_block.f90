!> The deck's MESH block: the mesh comes from a gmsh `.msh` file instead of
!! the ELEMENTS and NODES blocks.
!!
!!     MESH
!!     GMSH      plate.msh                      # path relative to the deck
!!     MATERIAL  plate                   1      # physical surface -> material
!!
!! Cards (keyword in columns 1-10):
!! * `GMSH`: the path in columns 11 to the end of the card (relative to the
!!   deck's folder unless it starts with `/`); exactly one.
!! * `MATERIAL`: physical surface name in columns 11-40, MATNO in 41-45; one
!!   card per physical surface of the mesh.
!! * `NODE`: an extra node of no element -- the reference node of a rigid
!!   body -- named in columns 11-30, at X (31-40), Y (41-50).  Extra nodes
!!   are numbered after the mesh's nodes in the order of their cards, and
!!   each becomes a node set of its name (for GROUP cards and RIGID's NREF).
!!
!! Errors in the cards are reported at the deck; errors in the mesh file at
!! the .msh file and line (see gmsh_reader).
module mesh_block
   use errors, only: error_list_t
   use strings, only: itoa, same_name
   use deck_lexer, only: deck_t, shown
   use kinds, only: dp
   use model, only: model_t, node_set_t, find_node_set
   use gmsh_reader, only: gmsh_mesh_t, read_gmsh, gmsh_to_model
   implicit none
   private
   public :: read_mesh_block, mesh_path

contains

   !> Read the MESH block's cards (up to the next block keyword) and the mesh.
   subroutine read_mesh_block(d, ickw, m, nnode_req, is_block_card, ok)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw             !! the MESH keyword card
      type(model_t), intent(inout) :: m       !! ntype, nmats, ngaus set; mesh filled here
      integer, intent(in) :: nnode_req        !! NNODE of the control card (0: any)
      interface
         logical function is_block_card(d, ic)
            import :: deck_t
            type(deck_t), intent(in) :: d
            integer, intent(in) :: ic
         end function is_block_card
      end interface
      logical, intent(out) :: ok              !! the mesh was read without error
      character(len=:), allocatable :: key, file, name
      character(len=64), allocatable :: names(:)
      integer, allocatable :: mats(:), lines(:)
      integer :: ic, imat, n0, nmat, k, gmsh_line, gmsh_card, nextra
      logical :: cok
      type(gmsh_mesh_t) :: msh
      character(len=20), allocatable :: xnames(:)
      integer, allocatable :: xlines(:)
      real(dp), allocatable :: xy(:, :)

      n0 = d%errors%n
      file = ''
      name = ''
      key = ''
      gmsh_line = 0
      gmsh_card = 0
      nmat = 0
      nextra = 0
      allocate (names(8), mats(8), lines(8), xnames(0), xlines(0), xy(2, 0))
      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         cok = .true.
         call d%get_word(ic, 1, 10, 'MESH', 'KEY', key, cok)
         if (.not. cok) cycle
         select case (key)
         case ('GMSH')
            if (gmsh_line /= 0) then
               call d%error_at(ic, 1, 'E-MESH', &
                               'MESH: a second GMSH card (the first is on line '// &
                               itoa(gmsh_line)//'); give one mesh file')
               cycle
            end if
            file = trim(adjustl(d%field_text(ic, 11, 100000)))
            gmsh_line = d%cards(ic)%line
            gmsh_card = ic
            if (len(file) == 0) then
               call d%error_at(ic, 11, 'E-MISSING', &
                               'MESH: GMSH expected the path of a .msh file in columns '// &
                               '11 onwards, found a blank field')
               gmsh_line = -1
            end if
         case ('MATERIAL')
            name = trim(adjustl(d%field_text(ic, 11, 40)))
            if (len(name) == 0) then
               call d%error_at(ic, 11, 'E-MISSING', &
                               'MESH: MATERIAL expected a physical surface name in '// &
                               'columns 11-40, found a blank field')
               cycle
            end if
            call d%get_int(ic, 41, 45, 'MESH/MATERIAL', 'MATNO', imat, cok)
            if (cok .and. len_trim(d%field_text(ic, 46, 100000)) > 0) then
               call d%error_at(ic, 46, 'E-EXTRA', &
                               'MESH/MATERIAL: expected the name (columns 11-40) and MATNO '// &
                               '(columns 41-45), found more: "'// &
                               shown(trim(adjustl(d%field_text(ic, 46, 100000))))//'"')
               cok = .false.
            end if
            if (.not. cok) cycle
            if (imat < 1 .or. imat > m%nmats) then
               call d%error_at(ic, 41, 'E-RANGE', &
                               'MESH/MATERIAL: MATNO (columns 41-45) expected 1..'// &
                               itoa(m%nmats)//' (NMATS), found '//itoa(imat))
               cycle
            end if
            do k = 1, nmat
               if (same_name(names(k), name)) then
                  call d%error_at(ic, 11, 'E-DUPLICATE', &
                                  'MESH/MATERIAL: physical surface "'//name// &
                                  '" is given twice (first on line '//itoa(lines(k))//')')
                  cok = .false.
               end if
            end do
            if (.not. cok) cycle
            if (nmat == size(names)) then
               names = [names, names]
               mats = [mats, mats]
               lines = [lines, lines]
            end if
            nmat = nmat + 1
            names(nmat) = name
            mats(nmat) = imat
            lines(nmat) = d%cards(ic)%line
         case ('NODE')
            call read_extra_node(d, ic, xnames, xlines, xy)
         case default
            call d%error_at(ic, 1, 'E-MESH', &
                            'MESH: expected a GMSH, MATERIAL or NODE card, found "'// &
                            shown(trim(d%cards(ic)%text))//'"')
         end select
      end do
      if (gmsh_line == 0) then
         call d%error_at(ickw, 1, 'E-MESH', 'MESH: the block has no GMSH card naming the mesh file')
      end if
      if (nmat == 0) call d%error_at(ickw, 1, 'E-MESH', &
                                     'MESH: the block has no MATERIAL card (one per '// &
                                     'physical surface: MATERIAL  <name, columns 11-40> <MATNO, &
                                     &columns 41-45>)')
      ok = d%errors%n == n0
      if (.not. ok) return

      m%mesh_file = mesh_path(d%file, file)
      call read_gmsh(m%mesh_file, msh, d%errors)
      if (d%errors%n == n0) call gmsh_to_model(msh, names(1:nmat), mats(1:nmat), lines(1:nmat), &
                                               d%file, &
                                               nnode_req, m, d%errors)
      ! an error about the mesh file as a whole (it cannot be opened, it has no
      ! 2-D elements, ...) has no line of its own: it is located at the GMSH card
      do k = n0 + 1, d%errors%n
         associate (e => d%errors%items(k))
            if (e%line > 0) cycle
            e%message = 'MESH: '//e%message
            e%file = d%file
            e%line = gmsh_line
            e%col = 11
            e%card = shown(trim(d%cards(gmsh_card)%text), 200)
         end associate
      end do
      if (d%errors%n == n0 .and. size(xnames) > 0) call add_extra_nodes(d, xnames, xlines, xy, m)
      ok = d%errors%n == n0
   end subroutine read_mesh_block

   !> NODE: an extra node, its name in columns 11-30 and X (31-40), Y (41-50);
   !! appended to the lists (a name given twice is reported).
   subroutine read_extra_node(d, ic, xnames, xlines, xy)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ic
      character(len=20), allocatable, intent(inout) :: xnames(:)
      integer, allocatable, intent(inout) :: xlines(:)   !! the cards (indices) of the extra nodes
      real(dp), allocatable, intent(inout) :: xy(:, :)
      character(len=:), allocatable :: name
      real(dp) :: x, y
      logical :: cok
      integer :: k
      cok = .true.
      name = trim(adjustl(d%field_text(ic, 11, 30)))
      if (len(name) == 0) then
         call d%error_at(ic, 11, 'E-MISSING', &
                         'MESH/NODE: field NAME (columns 11-30) expected the name of the '// &
                         'extra node, found a blank field')
         cok = .false.
      end if
      call d%get_real(ic, 31, 40, 'MESH/NODE', 'X', x, cok)
      call d%get_real(ic, 41, 50, 'MESH/NODE', 'Y', y, cok)
      if (cok) call d%check_coordinate(ic, 31, 'MESH/NODE', 'X', x, cok)
      if (cok) call d%check_coordinate(ic, 41, 'MESH/NODE', 'Y', y, cok)
      if (cok .and. len_trim(d%field_text(ic, 51, 100000)) > 0) then
         call d%error_at(ic, 51, 'E-EXTRA', &
                         'MESH/NODE: expected NAME (columns 11-30), X (31-40) and Y (41-50), '// &
                         'found more: "'//shown(trim(adjustl(d%field_text(ic, 51, 100000))))//'"')
         cok = .false.
      end if
      if (.not. cok) return
      do k = 1, size(xnames)
         if (same_name(trim(xnames(k)), name)) then
            call d%error_at(ic, 11, 'E-DUPLICATE', &
                            'MESH/NODE: the name "'//name//'" is given twice (first on line '// &
                            itoa(d%cards(xlines(k))%line)//')')
            return
         end if
      end do
      xnames = [character(len=20) :: xnames, name]
      xlines = [xlines, ic]
      xy = reshape([xy, x, y], [2, size(xlines)])
   end subroutine read_extra_node

   !> Append the extra nodes to the mesh read from the file: numbers
   !! npoin+1, ..., gmsh tag 0, the NODE card's line, and one node set each.
   !! A name that is already a set of the mesh is reported at its card.
   subroutine add_extra_nodes(d, xnames, xlines, xy, m)
      type(deck_t), intent(inout) :: d
      character(len=*), intent(in) :: xnames(:)
      integer, intent(in) :: xlines(:)              !! their cards (indices)
      real(dp), intent(in) :: xy(:, :)
      type(model_t), intent(inout) :: m
      type(node_set_t), allocatable :: tn(:)
      integer :: k, i, n0, np
      n0 = d%errors%n
      do k = 1, size(xnames)
         if (find_node_set(m, trim(xnames(k))) > 0) then
            call d%error_at(xlines(k), 11, 'E-DUPLICATE', &
                            'MESH/NODE: "'//trim(xnames(k))//'" is already a '// &
                            'physical group of '//m%mesh_file//'; give the extra node another name')
         end if
      end do
      if (d%errors%n > n0) return
      np = m%npoin
      m%coord = reshape([m%coord, xy], [2, np + size(xnames)])
      m%node_tag = [m%node_tag, (0, k=1, size(xnames))]
      m%node_line = [m%node_line, (d%cards(xlines(k))%line, k=1, size(xlines))]
      m%npoin = np + size(xnames)
      ! (component by component: gfortran 12 loses deferred-length character
      ! components in array constructors of derived types)
      allocate (tn(size(m%node_sets) + size(xnames)))
      do i = 1, size(m%node_sets)
         tn(i)%name = m%node_sets(i)%name
         tn(i)%nodes = m%node_sets(i)%nodes
      end do
      do k = 1, size(xnames)
         tn(size(m%node_sets) + k)%name = trim(xnames(k))
         tn(size(m%node_sets) + k)%nodes = [np + k]
      end do
      call move_alloc(tn, m%node_sets)
   end subroutine add_extra_nodes

   !> Path of a mesh file named in a deck: relative to the deck's folder.
   pure function mesh_path(deck_file, file) result(p)
      character(len=*), intent(in) :: deck_file, file
      character(len=:), allocatable :: p
      integer :: k
      logical :: absolute
      absolute = .false.
      if (len(file) > 0) absolute = file(1:1) == '/'
      k = index(deck_file, '/', back=.true.)
      if (absolute .or. k == 0) then
         p = file
      else
         p = deck_file(1:k)//file
      end if
   end function mesh_path

end module mesh_block
