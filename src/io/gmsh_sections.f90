!> The section parsers of a gmsh `.msh` file, ASCII formats 4.1 and 2.2.
!!
!! Owns the reading of `$MeshFormat` (version, ASCII, data size),
!! `$PhysicalNames`, `$Entities` (4.1: the physical tags of the entities),
!! `$Nodes` and `$Elements` (both formats) into a `gmsh_mesh_t`.  Each parser
!! starts after its header line, checks every line it reads through gmsh_text
!! and ends after its `$End` line; ok is false after an error (reported).
!! The order of the sections is gmsh_reader's (`read_gmsh`).
!!
!! Ref: gmsh reference manual, section "MSH file format" (versions 4.1 and 2.2).
module gmsh_sections
   use errors, only: error_list_t
   use strings, only: itoa
   use model, only: MAX_NODE
   use gmsh_text, only: msh_text_t, next_line, get_line, short, read_ints, check_count, tokens, &
                        line_reals, expect_end
   use gmsh_mesh, only: gmsh_mesh_t, entity_t, MAX_PHYS, alloc_nodes, alloc_elements, add_group, &
                        gmsh_nnode, type_name
   implicit none
   private

   public :: read_format, read_physical_names, read_entities
   public :: read_nodes41, read_nodes22, read_elements41, read_elements22

contains

   !> $MeshFormat: version 4.1 or 2.2, ASCII (file-type 0), data size 8.
   subroutine read_format(t, msh, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: il, b(2, 64), nt
      character(len=:), allocatable :: line, ver, ftype
      ok = .false.
      il = next_line(t)
      if (il == 0) then
         call errors%add('E-GMSH', 'truncated file: it ends inside $MeshFormat', file=t%path, &
                         line=t%nlines)
         return
      end if
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt /= 3) then
         call errors%add('E-GMSH', '$MeshFormat: expected "version file-type data-size" (e.g. '// &
                         '"4.1 0 8"), found "'//short(trim(line))//'"', file=t%path, line=il)
         return
      end if
      ver = line(b(1, 1):b(2, 1))
      ftype = line(b(1, 2):b(2, 2))
      if (ftype /= '0') then
         call errors%add('E-GMSH', 'binary .msh files are not supported (file-type '//ftype// &
                         '): save the mesh as ASCII, e.g. gmsh -2 -format msh41 file.geo, or '// &
                         'with Mesh.Binary = 0', file=t%path, line=il)
         return
      end if
      if (ver == '4.1' .or. ver == '4.10') then
         msh%version = '4.1'
      else if (ver == '2.2' .or. ver == '2.20') then
         msh%version = '2.2'
      else
         call errors%add('E-GMSH', 'unsupported .msh format version '//ver// &
                         ': expected 4.1 or 2.2 (ASCII); export with gmsh -format msh41 or msh22', &
                         file=t%path, line=il)
         return
      end if
      if (line(b(1, 3):b(2, 3)) /= '8') then
         call errors%add('E-GMSH', '$MeshFormat: data-size '//line(b(1, 3):b(2, 3))// &
                         ' is not supported (expected 8)', file=t%path, line=il)
         return
      end if
      ok = .true.
      call expect_end(t, 'MeshFormat', errors, ok)
   end subroutine read_format

   !> $PhysicalNames: number, then "dim tag "name"" per line.
   subroutine read_physical_names(t, msh, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(2), il, n, k, q1, q2
      character(len=:), allocatable :: line
      ok = .true.
      call read_ints(t, 'PhysicalNames', 'the number of physical names', 1, v, errors, ok, il)
      call check_count(t, 'PhysicalNames', 'physical names', v(1), 1, il, errors, ok)
      if (.not. ok) return
      n = v(1)
      do k = 1, n
         call read_ints(t, 'PhysicalNames', 'a line "dimension tag ""name"""', 2, v, errors, ok, &
                        il, at_least=.true.)
         if (.not. ok) return
         line = get_line(t, il)
         q1 = index(line, '"')
         q2 = index(line, '"', back=.true.)
         if (q1 == 0 .or. q2 <= q1) then
            call errors%add('E-GMSH', '$PhysicalNames: expected a quoted name after dimension '// &
                            'and tag, found "'//short(trim(line))//'"', file=t%path, line=il)
            ok = .false.
            return
         end if
         call add_group(msh, v(1), v(2), line(q1 + 1:q2 - 1))
      end do
      call expect_end(t, 'PhysicalNames', errors, ok)
   end subroutine read_physical_names

   !> $Entities (4.1): the physical tags of every point, curve and surface.
   subroutine read_entities(t, ents, nent, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(entity_t), allocatable, intent(inout) :: ents(:, :)
      integer, intent(out) :: nent(0:3)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(4), il, dim, k, nphys, first, j, ios, nt, b(2, 64)
      character(len=:), allocatable :: line
      ok = .true.
      call read_ints(t, 'Entities', 'numPoints numCurves numSurfaces numVolumes', 4, v, errors, &
                     ok, il)
      do dim = 1, 4
         call check_count(t, 'Entities', 'entities', v(dim), 1, il, errors, ok)
      end do
      if (.not. ok) return
      nent = v
      deallocate (ents)
      allocate (ents(max(1, maxval(v)), 0:3))
      do dim = 0, 3
         do k = 1, nent(dim)
            il = next_line(t)
            if (il == 0) then
               call errors%add('E-GMSH', 'truncated file: it ends inside $Entities', file=t%path, &
                               line=t%nlines)
               ok = .false.
               return
            end if
            line = get_line(t, il)
            call tokens(line, b, nt)
            ! point: tag x y z nphys tags...; others: tag 6 bounds nphys tags... nbound tags...
            first = merge(5, 8, dim == 0)
            if (nt < first) then
               call errors%add('E-GMSH', '$Entities: expected an entity of dimension '// &
                               itoa(dim)//', found "'//short(trim(line))//'"', file=t%path, &
                               line=il)
               ok = .false.
               return
            end if
            read (line(b(1, 1):b(2, 1)), *, iostat=ios) ents(k, dim)%tag
            if (ios == 0) read (line(b(1, first):b(2, first)), *, iostat=ios) nphys
            if (ios /= 0 .or. nphys < 0 .or. nt < first + max(nphys, 0)) then
               call errors%add('E-GMSH', '$Entities: cannot read the tag and physical tags of "'// &
                               short(trim(line))//'"', file=t%path, line=il)
               ok = .false.
               return
            end if
            if (nphys > MAX_PHYS) then
               call errors%add('E-GMSH', '$Entities: an entity belongs to '//itoa(nphys)// &
                               ' physical groups; at most '//itoa(MAX_PHYS)//' are supported', &
                               file=t%path, line=il)
               ok = .false.
               return
            end if
            ents(k, dim)%nphys = nphys
            do j = 1, nphys
               read (line(b(1, first + j):b(2, first + j)), *, iostat=ios) ents(k, dim)%phys(j)
               if (ios /= 0) then
                  call errors%add('E-GMSH', '$Entities: physical tag '//itoa(j)//' of entity '// &
                                  itoa(ents(k, dim)%tag)//': expected an integer, found "'// &
                                  short(line(b(1, first + j):b(2, first + j)))//'"', file=t%path, &
                                  line=il)
                  ok = .false.
                  return
               end if
               ents(k, dim)%phys(j) = abs(ents(k, dim)%phys(j))
            end do
         end do
      end do
      call expect_end(t, 'Entities', errors, ok)
   end subroutine read_entities

   !> $Nodes, format 4.1: entity blocks of tags then coordinates.
   subroutine read_nodes41(t, msh, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(4), il, nblk, ib, nin, k, n, param, tagline(1)
      ok = .true.
      call read_ints(t, 'Nodes', 'numEntityBlocks numNodes minNodeTag maxNodeTag', 4, v, errors, &
                     ok, il)
      call check_count(t, 'Nodes', 'entity blocks', v(1), 1, il, errors, ok)
      call check_count(t, 'Nodes', 'nodes', v(2), 2, il, errors, ok)
      if (.not. ok) return
      nblk = v(1)
      call alloc_nodes(msh, v(2))
      n = 0
      do ib = 1, nblk
         call read_ints(t, 'Nodes', 'an entity block header "entityDim entityTag parametric '// &
                        'numNodesInBlock"', 4, v, errors, ok, il)
         if (.not. ok) return
         param = v(3)
         nin = v(4)
         call check_count(t, 'Nodes', 'nodes in the block', nin, 2, il, errors, ok)
         if (.not. ok) return
         if (param /= 0) then
            call errors%add('E-GMSH', '$Nodes: parametric node coordinates are not supported; '// &
                            'save without Mesh.SaveParametric', file=t%path, line=il)
            ok = .false.
            return
         end if
         if (n + nin > msh%nnodes) then
            call errors%add('E-GMSH', '$Nodes: the blocks hold more nodes than the '// &
                            itoa(msh%nnodes)//' declared', file=t%path, line=il)
            ok = .false.
            return
         end if
         do k = 1, nin
            call read_ints(t, 'Nodes', 'a node tag', 1, tagline, errors, ok, il)
            if (.not. ok) return
            msh%node_tag(n + k) = tagline(1)
         end do
         do k = 1, nin
            il = next_line(t)
            if (il == 0) then
               call errors%add('E-GMSH', 'truncated file: it ends inside $Nodes (expected x y z)', &
                               file=t%path, line=t%nlines)
               ok = .false.
               return
            end if
            call line_reals(t, il, 'Nodes', 'node coordinates "x y z"', 1, 3, msh%xyz(:, n + k), &
                            errors, ok)
            if (.not. ok) return
            msh%node_line(n + k) = il
         end do
         n = n + nin
      end do
      if (n /= msh%nnodes) then
         call errors%add('E-GMSH', '$Nodes: '//itoa(msh%nnodes)// &
                         ' nodes declared, the blocks hold '//itoa(n), file=t%path, line=il)
         ok = .false.
         return
      end if
      call expect_end(t, 'Nodes', errors, ok)
   end subroutine read_nodes41

   !> $Nodes, format 2.2: number, then "tag x y z" per line.
   subroutine read_nodes22(t, msh, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(1), il, k
      ok = .true.
      call read_ints(t, 'Nodes', 'the number of nodes', 1, v, errors, ok, il)
      call check_count(t, 'Nodes', 'nodes', v(1), 1, il, errors, ok)
      if (.not. ok) return
      call alloc_nodes(msh, v(1))
      do k = 1, msh%nnodes
         call read_ints(t, 'Nodes', 'a node line "tag x y z"', 1, v, errors, ok, il, &
                        at_least=.true.)
         if (.not. ok) return
         msh%node_tag(k) = v(1)
         call line_reals(t, il, 'Nodes', 'a node line "tag x y z"', 2, 3, msh%xyz(:, k), errors, ok)
         if (.not. ok) return
         msh%node_line(k) = il
      end do
      call expect_end(t, 'Nodes', errors, ok)
   end subroutine read_nodes22

   !> $Elements, format 4.1: entity blocks; the physical tags come from $Entities.
   subroutine read_elements41(t, msh, ents, nent, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(entity_t), intent(in) :: ents(:, 0:)
      integer, intent(in) :: nent(0:3)
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(MAX_NODE + 1), il, nblk, ib, edim, etag, ety, nin, k, n, nn, ie, j
      ok = .true.
      call read_ints(t, 'Elements', 'numEntityBlocks numElements minElementTag maxElementTag', 4, &
                     v, errors, ok, il)
      call check_count(t, 'Elements', 'entity blocks', v(1), 1, il, errors, ok)
      call check_count(t, 'Elements', 'elements', v(2), 1, il, errors, ok)
      if (.not. ok) return
      nblk = v(1)
      call alloc_elements(msh, v(2))
      n = 0
      do ib = 1, nblk
         call read_ints(t, 'Elements', 'an entity block header "entityDim entityTag '// &
                        'elementType numElementsInBlock"', 4, v, errors, ok, il)
         if (.not. ok) return
         edim = v(1)
         etag = v(2)
         ety = v(3)
         nin = v(4)
         call check_count(t, 'Elements', 'elements in the block', nin, 1, il, errors, ok)
         if (.not. ok) return
         nn = gmsh_nnode(ety)
         if (nn == 0) then
            call errors%add('E-GMSH', 'unsupported element type '//itoa(ety)//' ('// &
                            type_name(ety)//'): Kontakt2D takes 3-node triangles, 4-, 8- and '// &
                            '9-node quadrilaterals, and points and 2- or 3-node lines for '// &
                            'physical groups', file=t%path, line=il)
            ok = .false.
            return
         end if
         if (n + nin > msh%nelems) then
            call errors%add('E-GMSH', '$Elements: the blocks hold more elements than the '// &
                            itoa(msh%nelems)//' declared', file=t%path, line=il)
            ok = .false.
            return
         end if
         ! physical tags of the entity
         ie = 0
         if (edim >= 0 .and. edim <= 3) then
            do j = 1, nent(edim)
               if (ents(j, edim)%tag == etag) ie = j
            end do
         end if
         do k = 1, nin
            call read_ints(t, 'Elements', 'an element line "tag node1 ... node'//itoa(nn)// &
                           '" of type '//itoa(ety), 1 + nn, v, errors, ok, il)
            if (.not. ok) return
            msh%etype(n + k) = ety
            msh%enodes(1:nn, n + k) = v(2:1 + nn)
            msh%eline(n + k) = il
            if (ie > 0) then
               msh%nphys(n + k) = ents(ie, edim)%nphys
               msh%ephys(:, n + k) = ents(ie, edim)%phys
            end if
         end do
         n = n + nin
      end do
      if (n /= msh%nelems) then
         call errors%add('E-GMSH', '$Elements: '//itoa(msh%nelems)// &
                         ' elements declared, the blocks hold '//itoa(n), file=t%path, line=il)
         ok = .false.
         return
      end if
      call expect_end(t, 'Elements', errors, ok)
   end subroutine read_elements41

   !> $Elements, format 2.2: "tag type ntags physical elementary ... nodes".
   subroutine read_elements22(t, msh, errors, ok)
      type(msh_text_t), intent(inout) :: t
      type(gmsh_mesh_t), intent(inout) :: msh
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: v(3 + 16 + MAX_NODE), il, k, ety, ntags, nn
      ok = .true.
      call read_ints(t, 'Elements', 'the number of elements', 1, v, errors, ok, il)
      call check_count(t, 'Elements', 'elements', v(1), 1, il, errors, ok)
      if (.not. ok) return
      call alloc_elements(msh, v(1))
      do k = 1, msh%nelems
         call read_ints(t, 'Elements', 'an element line "tag type ntags tags... nodes..."', 3, v, &
                        errors, ok, il, at_least=.true.)
         if (.not. ok) return
         ety = v(2)
         ntags = v(3)
         nn = gmsh_nnode(ety)
         if (nn == 0) then
            call errors%add('E-GMSH', 'unsupported element type '//itoa(ety)//' ('// &
                            type_name(ety)//'): Kontakt2D takes 3-node triangles, 4-, 8- and '// &
                            '9-node quadrilaterals, and points and 2- or 3-node lines for '// &
                            'physical groups', file=t%path, line=il)
            ok = .false.
            return
         end if
         if (ntags < 0 .or. ntags > 16) then
            call errors%add('E-GMSH', '$Elements: invalid number of tags '//itoa(ntags), &
                            file=t%path, line=il)
            ok = .false.
            return
         end if
         t%pos = t%pos - 1
         call read_ints(t, 'Elements', 'an element line with '//itoa(ntags)//' tags and '// &
                        itoa(nn)//' nodes', 3 + ntags + nn, v, errors, ok, il)
         if (.not. ok) return
         msh%etype(k) = ety
         msh%enodes(1:nn, k) = v(4 + ntags:3 + ntags + nn)
         msh%eline(k) = il
         if (ntags >= 1) then
            if (v(4) /= 0) then
               msh%nphys(k) = 1
               msh%ephys(1, k) = v(4)
            end if
         end if
      end do
      call expect_end(t, 'Elements', errors, ok)
   end subroutine read_elements22

end module gmsh_sections
