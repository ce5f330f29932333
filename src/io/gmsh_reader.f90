!> Reader of gmsh `.msh` meshes, ASCII formats 4.1 and 2.2.
!!
!! Two steps.  `read_gmsh` parses the file into a `gmsh_mesh_t` (nodes with
!! their tags, physical names, elements with their physical tags), checking
!! every line it reads; `gmsh_to_model` then builds the analysis mesh:
!!
!! * the 2-D elements (3-node triangles, 4-, 8- and 9-node quadrilaterals)
!!   become the model's elements, their material taken from the physical
!!   surface they belong to through the deck's MATERIAL cards;
!! * the nodes they use are numbered 1..npoin in increasing tag order; the
!!   gmsh tags are kept in `node_tag` for the output;
!! * clockwise elements are reordered to anticlockwise (corners reversed,
!!   midside nodes following their edges), so that det J > 0;
!! * every physical curve becomes a node set and an edge set (each of its
!!   line elements located as an edge of a 2-D element), every physical
!!   point a node set.
!!
!! gmsh's node order of the quadrilaterals (corners, then the midside nodes
!! of edges 1-2, 2-3, 3-4, 4-1, then the centre) is Kontakt2D's.  6-node
!! triangles, 3-D elements, binary files and any other element type are
!! rejected.  Every error names the .msh file and the line.
!!
!! Ref: gmsh reference manual, section "MSH file format" (versions 4.1 and 2.2).
!!
!! This module owns the two steps' entry points: the order of the sections
!! (`read_gmsh`) and the translation's top level (`gmsh_to_model`: the 2-D
!! elements taken, their materials assigned).  The rest lives in rooms of its
!! own: gmsh_text (lines and tokens), gmsh_sections (the section parsers),
!! gmsh_mesh (the parsed content, groups and element-type table),
!! gmsh_numbering (nodes, connectivity, orientation) and gmsh_sets (the
!! node and edge sets of the physical groups).
module gmsh_reader
   use errors, only: error_list_t
   use strings, only: itoa, same_name
   use model, only: model_t
   use gmsh_text, only: msh_text_t, load, next_line, get_line, short, skip_section
   use gmsh_mesh, only: gmsh_mesh_t, gmsh_group_t, entity_t, complete_groups, find_group, &
                        gmsh_nnode, gmsh_dim, group_by_name, group_list
   use gmsh_sections, only: read_format, read_physical_names, read_entities, read_nodes41, &
                            read_nodes22, read_elements41, read_elements22
   use gmsh_numbering, only: number_nodes
   use gmsh_sets, only: node_elements, build_sets
   implicit none
   private

   public :: gmsh_mesh_t, gmsh_group_t, read_gmsh, gmsh_to_model, gmsh_nnode

contains

   ! ================================================================== step 1: the file

   !> Parse a .msh file.  On return `errors%n` > 0 means the mesh is unusable.
   subroutine read_gmsh(path, msh, errors)
      character(len=*), intent(in) :: path
      type(gmsh_mesh_t), intent(out) :: msh
      type(error_list_t), intent(inout) :: errors
      type(msh_text_t) :: t
      type(entity_t), allocatable :: ents(:, :)      ! (max entities, 0:3) by dimension
      integer :: nent(0:3), n0, il
      character(len=:), allocatable :: line, section
      logical :: ok, have_format, have_nodes, have_elements

      msh%path = path
      allocate (msh%groups(0), ents(0, 0:3))
      nent = 0
      n0 = errors%n
      call load(t, path, errors, ok)
      if (.not. ok) return
      have_format = .false.
      have_nodes = .false.
      have_elements = .false.
      do while (t%pos < t%nlines)
         il = next_line(t)
         line = trim(adjustl(get_line(t, il)))
         if (len(line) == 0) cycle
         if (line(1:1) /= '$') then
            call err(il, 'expected a section header ($MeshFormat, $Nodes, ...), found "'// &
                     short(line)//'"')
            return
         end if
         section = line(2:)
         select case (section)
         case ('MeshFormat')
            call read_format(t, msh, errors, ok)
            if (.not. ok) return
            have_format = .true.
         case ('PhysicalNames')
            if (.not. need_format()) return
            call read_physical_names(t, msh, errors, ok)
         case ('Entities')
            if (.not. need_format()) return
            if (msh%version == '4.1') then
               call read_entities(t, ents, nent, errors, ok)
            else
               call skip_section(t, section, errors, ok)
            end if
         case ('Nodes')
            if (.not. need_format()) return
            if (msh%version == '4.1') then
               call read_nodes41(t, msh, errors, ok)
            else
               call read_nodes22(t, msh, errors, ok)
            end if
            have_nodes = ok
         case ('Elements')
            if (.not. need_format()) return
            if (msh%version == '4.1') then
               call read_elements41(t, msh, ents, nent, errors, ok)
            else
               call read_elements22(t, msh, errors, ok)
            end if
            have_elements = ok
         case default
            if (.not. need_format()) return
            call skip_section(t, section, errors, ok)   ! $Periodic, $NodeData, ...: not used
         end select
         if (.not. ok) return
      end do
      if (.not. have_format) then
         call err(max(t%nlines, 1), 'not a gmsh mesh: no $MeshFormat section')
      else if (.not. have_nodes) then
         call err(max(t%nlines, 1), 'the file has no $Nodes section')
      else if (.not. have_elements) then
         call err(max(t%nlines, 1), 'the file has no $Elements section')
      end if
      if (errors%n > n0) return
      call complete_groups(msh)
   contains
      logical function need_format()
         need_format = allocated(msh%version)
         if (.not. need_format) call err(il, 'expected $MeshFormat first, found "'//short(line)// &
                                         '"')
      end function need_format
      subroutine err(l, msg)
         integer, intent(in) :: l
         character(len=*), intent(in) :: msg
         call errors%add('E-GMSH', msg, file=path, line=l)
      end subroutine err
   end subroutine read_gmsh

   ! ================================================================== step 2: the model

   !> Build the model's mesh and named sets from a parsed .msh file.
   !!
   !! `mat_names(k)` (physical surface) gets material `mat_numbers(k)`; the
   !! deck lines `mat_lines(k)` of the MATERIAL cards locate errors in the deck
   !! `deck_file`.  `nnode_req` > 0 requires every element to have that many
   !! nodes.  Errors go to `errors` (file and line in the .msh or the deck).
   !! Whether the control card's NGAUS suits the elements is checked after
   !! reading (driver/model_input), with the element kernels.
   subroutine gmsh_to_model(msh, mat_names, mat_numbers, mat_lines, deck_file, nnode_req, m, errors)
      type(gmsh_mesh_t), intent(in) :: msh
      character(len=*), intent(in) :: mat_names(:)
      integer, intent(in) :: mat_numbers(:), mat_lines(:)
      character(len=*), intent(in) :: deck_file
      integer, intent(in) :: nnode_req
      type(model_t), intent(inout) :: m
      type(error_list_t), intent(inout) :: errors
      integer, allocatable :: surf(:), tags(:), model_of(:), eptr(:), elist(:)
      integer :: k, g, n0
      logical :: ok

      n0 = errors%n
      ! every MATERIAL card names a physical surface of the file
      do k = 1, size(mat_names)
         g = group_by_name(msh, 2, mat_names(k))
         if (g == 0) call errors%add('E-GMSH', 'MESH: MATERIAL names physical surface "'// &
                                     trim(mat_names(k))//'", which '//msh%path// &
                                     ' does not have (its physical surfaces: '// &
                                     group_list(msh, 2)//')', file=deck_file, line=mat_lines(k), &
                                     col=11)
      end do
      call surface_elements(msh, nnode_req, surf, errors, ok)
      if (.not. ok .or. errors%n > n0) return
      if (allocated(m%matno)) deallocate (m%matno)
      allocate (m%matno(size(surf)))
      call assign_materials(msh, surf, mat_names, mat_numbers, deck_file, m%matno, errors)
      if (errors%n > n0) return
      call number_nodes(msh, surf, m, tags, model_of, errors, ok)
      if (.not. ok) return
      call node_elements(m, eptr, elist)
      ! physical curves and points: node sets and edge sets
      allocate (m%node_sets(0), m%edge_sets(0))
      do g = 1, size(msh%groups)
         if (msh%groups(g)%dim > 1) cycle
         call build_sets(msh, g, tags, model_of, eptr, elist, m, errors)
         if (errors%n > n0) return
      end do
   end subroutine gmsh_to_model

   !> The 2-D elements of the file (surf: their indices in msh), all linear
   !! or all quadratic, with nnode_req nodes when that is > 0.  ok is false
   !! when the file has none (reported).
   subroutine surface_elements(msh, nnode_req, surf, errors, ok)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: nnode_req              !! NNODE of the control card (0: any)
      integer, allocatable, intent(out) :: surf(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: k, nn, nsurf, nq, nl

      allocate (surf(msh%nelems))
      nsurf = 0
      nq = 0
      nl = 0
      do k = 1, msh%nelems
         if (gmsh_dim(msh%etype(k)) /= 2) cycle
         nsurf = nsurf + 1
         surf(nsurf) = k
         nn = gmsh_nnode(msh%etype(k))
         if (nn >= 8) then
            nq = nq + 1
         else
            nl = nl + 1
         end if
         if (nnode_req > 0 .and. nn /= nnode_req) then
            call errors%add('E-GMSH', itoa(nn)//'-node element, but NNODE = '//itoa(nnode_req)// &
                            ' on the control card requires '//itoa(nnode_req)// &
                            '-node elements only', file=msh%path, line=msh%eline(k))
            exit
         end if
      end do
      surf = surf(1:nsurf)
      ok = nsurf > 0
      if (.not. ok) then
         call errors%add('E-GMSH', 'the mesh has no 2-D elements (triangles or '// &
                         'quadrilaterals): mesh the surfaces (gmsh -2) and put them in '// &
                         'physical surfaces', file=msh%path)
         return
      end if
      if (nq > 0 .and. nl > 0) then
         call errors%add('E-GMSH', 'the mesh mixes linear (3-, 4-node) and quadratic (8-, '// &
                         '9-node) elements, which do not conform along their common edges', &
                         file=msh%path)
      end if
   end subroutine surface_elements

   !> Material of every 2-D element surf(ie): that of the MATERIAL card naming
   !! one of its physical surfaces (0 where none does; reported).
   subroutine assign_materials(msh, surf, mat_names, mat_numbers, deck_file, matno, errors)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: surf(:)
      character(len=*), intent(in) :: mat_names(:)
      integer, intent(in) :: mat_numbers(:)
      character(len=*), intent(in) :: deck_file
      integer, intent(out) :: matno(:)               !! (size(surf))
      type(error_list_t), intent(inout) :: errors
      logical :: unmapped_reported(size(msh%groups))
      integer :: ie, k, j, g, kg, imat

      unmapped_reported = .false.
      matno = 0
      do ie = 1, size(surf)
         k = surf(ie)
         imat = 0
         if (msh%nphys(k) == 0) then
            call errors%add('E-GMSH', 'element of no physical surface: every surface must '// &
                            'belong to a physical surface named on a MATERIAL card', &
                            file=msh%path, line=msh%eline(k))
            exit
         end if
         do j = 1, msh%nphys(k)
            g = find_group(msh, 2, msh%ephys(j, k))
            kg = 0
            if (g > 0) kg = name_index(mat_names, msh%groups(g)%name)
            if (kg > 0) then
               if (imat /= 0 .and. imat /= mat_numbers(kg)) then
                  call errors%add('E-GMSH', 'element in two physical surfaces with different '// &
                                  'materials', file=msh%path, line=msh%eline(k))
               end if
               imat = mat_numbers(kg)
            end if
         end do
         if (imat == 0) then
            g = find_group(msh, 2, msh%ephys(1, k))
            if (g > 0) then
               if (.not. unmapped_reported(g)) then
                  unmapped_reported(g) = .true.
                  call errors%add('E-GMSH', 'physical surface "'//msh%groups(g)%name// &
                                  '" has no MATERIAL card in the MESH block of '//deck_file, &
                                  file=msh%path, line=msh%eline(k))
               end if
            end if
         end if
         matno(ie) = imat
      end do
   end subroutine assign_materials

   !> Index of `name` in `names` (case-insensitive), 0 if absent.
   pure integer function name_index(names, name)
      character(len=*), intent(in) :: names(:), name
      integer :: q
      name_index = 0
      do q = 1, size(names)
         if (same_name(names(q), name)) then
            name_index = q
            return
         end if
      end do
   end function name_index

end module gmsh_reader
