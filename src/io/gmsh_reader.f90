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
module gmsh_reader
   use, intrinsic :: ieee_exceptions, only: ieee_overflow, ieee_get_halting_mode, ieee_set_halting_mode, &
                                            ieee_set_flag
   use, intrinsic :: ieee_arithmetic, only: ieee_is_finite
   use kinds, only: dp
   use errors, only: error_list_t
   use strings, only: itoa, rtoa, same_name
   use model, only: model_t, node_set_t, edge_set_t, MAX_NODE
   use topology, only: element_edge_nodes, nedges
   use deck_lexer, only: MAX_COORDINATE
   implicit none
   private

   public :: gmsh_mesh_t, gmsh_group_t, read_gmsh, gmsh_to_model, gmsh_nnode

   integer, parameter :: MAX_PHYS = 8   !! physical tags kept per element

   !> A physical group: dimension, tag and name ('' when the file names none).
   type :: gmsh_group_t
      integer :: dim = 0
      integer :: tag = 0
      character(len=:), allocatable :: name
   end type gmsh_group_t

   !> The content of a .msh file that Kontakt2D uses.
   type :: gmsh_mesh_t
      character(len=:), allocatable :: path
      character(len=:), allocatable :: version        !! '4.1' or '2.2'
      integer :: nnodes = 0
      integer, allocatable :: node_tag(:)             !! (nnodes)
      real(dp), allocatable :: xyz(:, :)              !! (3, nnodes)
      integer, allocatable :: node_line(:)            !! line of each node in the file
      integer :: nelems = 0
      integer, allocatable :: etype(:)                !! gmsh element type
      integer, allocatable :: enodes(:, :)            !! (MAX_NODE, nelems) node tags
      integer, allocatable :: nphys(:)                !! number of physical tags
      integer, allocatable :: ephys(:, :)             !! (MAX_PHYS, nelems) physical tags
      integer, allocatable :: eline(:)                !! line of each element in the file
      type(gmsh_group_t), allocatable :: groups(:)    !! from $PhysicalNames and the elements
   end type gmsh_mesh_t

   !> Lines of the file with a cursor.
   type :: msh_text_t
      character(len=:), allocatable :: path
      character(len=:), allocatable :: buf            !! the whole file
      integer, allocatable :: lstart(:), lend(:)      !! bounds of each line in buf
      integer :: nlines = 0
      integer :: pos = 0                              !! last line consumed
   end type msh_text_t

   !> An entity of a 4.1 file: its physical tags.
   type :: entity_t
      integer :: tag = 0
      integer :: nphys = 0
      integer :: phys(MAX_PHYS) = 0
   end type entity_t

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
            call err(il, 'expected a section header ($MeshFormat, $Nodes, ...), found "'//short(line)//'"')
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
         if (.not. need_format) call err(il, 'expected $MeshFormat first, found "'//short(line)//'"')
      end function need_format
      subroutine err(l, msg)
         integer, intent(in) :: l
         character(len=*), intent(in) :: msg
         call errors%add('E-GMSH', msg, file=path, line=l)
      end subroutine err
   end subroutine read_gmsh

   !> Read the whole file; split it into lines.
   subroutine load(t, path, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: path
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: u, ios, fsize, i, n, s
      logical :: exists
      character(len=256) :: msg

      ok = .false.
      t%path = path
      inquire (file=path, exist=exists)
      if (.not. exists) then
         call errors%add('E-GMSH', 'cannot open mesh file "'//path//'": it does not exist', file=path)
         return
      end if
      open (newunit=u, file=path, access='stream', form='unformatted', status='old', action='read', &
            iostat=ios, iomsg=msg)
      if (ios /= 0) then
         call errors%add('E-GMSH', 'cannot open mesh file: '//trim(msg), file=path)
         return
      end if
      inquire (unit=u, size=fsize)
      fsize = max(fsize, 0)
      allocate (character(len=fsize) :: t%buf)
      if (fsize > 0) read (u, iostat=ios, iomsg=msg) t%buf
      close (u)
      if (ios /= 0) then
         call errors%add('E-GMSH', 'cannot read mesh file: '//trim(msg), file=path)
         return
      end if
      n = 1
      do i = 1, fsize
         if (t%buf(i:i) == achar(10)) n = n + 1
      end do
      allocate (t%lstart(n), t%lend(n))
      n = 0
      s = 1
      do i = 1, fsize + 1
         if (i > fsize) then
            if (s <= fsize) then
               n = n + 1
               t%lstart(n) = s
               t%lend(n) = fsize
            end if
            exit
         end if
         if (t%buf(i:i) == achar(10)) then
            n = n + 1
            t%lstart(n) = s
            t%lend(n) = i - 1
            if (i - 1 >= s) then
               if (t%buf(i - 1:i - 1) == achar(13)) t%lend(n) = i - 2
            end if
            s = i + 1
         end if
      end do
      t%nlines = n
      t%pos = 0
      ok = .true.
   end subroutine load

   integer function next_line(t) result(il)
      type(msh_text_t), intent(inout) :: t
      il = 0
      if (t%pos >= t%nlines) return
      t%pos = t%pos + 1
      il = t%pos
   end function next_line

   function get_line(t, il) result(s)
      type(msh_text_t), intent(in) :: t
      integer, intent(in) :: il
      character(len=:), allocatable :: s
      if (il < 1 .or. il > t%nlines) then
         s = ''
      else
         s = t%buf(t%lstart(il):t%lend(il))
      end if
   end function get_line

   !> First 60 characters of a line, for messages.
   pure function short(s) result(r)
      character(len=*), intent(in) :: s
      character(len=:), allocatable :: r
      if (len(s) > 60) then
         r = s(1:60)//'...'
      else
         r = s
      end if
   end function short

   !> Next line of a section, split into integers (and reals when `reals` is given).
   !! Reports a truncated file or a line with the wrong number of values.
   subroutine read_ints(t, section, what, n, v, errors, ok, il, at_least)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section, what
      integer, intent(in) :: n                     !! number of integers expected
      integer, intent(out) :: v(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      integer, intent(out) :: il
      logical, intent(in), optional :: at_least    !! more values than n are allowed
      character(len=:), allocatable :: line
      integer :: k, ios, nt
      integer :: b(2, 64)

      il = next_line(t)
      if (il == 0) then
         call errors%add('E-GMSH', 'truncated file: it ends inside $'//section//' (expected '//what//')', &
                         file=t%path, line=t%nlines)
         ok = .false.
         return
      end if
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt < n .or. (nt > n .and. .not. present(at_least))) then
         if (nt >= 1) then
            if (line(b(1, 1):b(1, 1)) == '$') then
               call errors%add('E-GMSH', '$'//section//' ends early: expected '//what//', found "'// &
                               short(trim(line))//'"', file=t%path, line=il)
               ok = .false.
               return
            end if
         end if
         call errors%add('E-GMSH', '$'//section//': expected '//what//' ('//itoa(n)//' integers), found "'// &
                         short(trim(line))//'"', file=t%path, line=il)
         ok = .false.
         return
      end if
      do k = 1, n
         read (line(b(1, k):b(2, k)), *, iostat=ios) v(k)
         if (ios /= 0 .or. .not. is_int(line(b(1, k):b(2, k)))) then
            call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'//line(b(1, k):b(2, k))// &
                            '" where an integer belongs', file=t%path, line=il)
            ok = .false.
            return
         end if
      end do
   end subroutine read_ints

   !> A count read from the file is bounded by what the file can still hold:
   !! `per` lines per entry after line il (a negative count is an error too),
   !! so that no array is sized from a count the file cannot back.
   subroutine check_count(t, section, what, n, per, il, errors, ok)
      type(msh_text_t), intent(in) :: t
      character(len=*), intent(in) :: section, what   !! section name, what is counted
      integer, intent(in) :: n                        !! the count
      integer, intent(in) :: per                      !! lines each entry takes at least
      integer, intent(in) :: il                       !! line of the count
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      if (.not. ok) return
      if (n < 0) then
         call errors%add('E-GMSH', '$'//section//': expected a number of '//what//' >= 0, found '//itoa(n), &
                         file=t%path, line=il)
         ok = .false.
      else if (n > (t%nlines - il)/per) then
         call errors%add('E-GMSH', 'truncated file: it ends inside $'//section//' ('//itoa(n)//' '//what// &
                         ' declared, the file has only '//itoa(t%nlines - il)//' more lines)', file=t%path, line=il)
         ok = .false.
      end if
   end subroutine check_count

   !> Blank-separated tokens of a line: bounds b(1:2, k), count nt (at most size(b, 2)).
   pure subroutine tokens(line, b, nt)
      character(len=*), intent(in) :: line
      integer, intent(out) :: b(:, :)
      integer, intent(out) :: nt
      integer :: i, n
      logical :: inword
      nt = 0
      inword = .false.
      n = len(line)
      do i = 1, n
         if (line(i:i) == ' ' .or. line(i:i) == achar(9)) then
            if (inword) b(2, nt) = i - 1
            inword = .false.
         else if (.not. inword) then
            if (nt == size(b, 2)) return
            nt = nt + 1
            b(1, nt) = i
            b(2, nt) = n
            inword = .true.
         end if
      end do
   end subroutine tokens

   pure logical function is_int(s)
      character(len=*), intent(in) :: s
      integer :: i, i0
      is_int = .false.
      if (len(s) == 0) return
      i0 = 1
      if (s(1:1) == '-' .or. s(1:1) == '+') i0 = 2
      if (i0 > len(s)) return
      do i = i0, len(s)
         if (s(i:i) < '0' .or. s(i:i) > '9') return
      end do
      is_int = .true.
   end function is_int

   !> Reals of a line (tokens first..first+n-1).
   subroutine line_reals(t, il, section, what, first, n, x, errors, ok)
      type(msh_text_t), intent(in) :: t
      integer, intent(in) :: il, first, n
      character(len=*), intent(in) :: section, what
      real(dp), intent(out) :: x(:)
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      character(len=:), allocatable :: line
      integer :: b(2, 64), nt, k, ios
      logical :: halt
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt < first + n - 1) then
         call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'//short(trim(line))//'"', &
                         file=t%path, line=il)
         ok = .false.
         return
      end if
      do k = 1, n
         associate (tok => line(b(1, first + k - 1):b(2, first + k - 1)))
            ! a literal beyond the range of real(dp) overflows inside the
            ! conversion: with overflow trapping on (Debug builds) that would stop
            ! the program before the check below could report it
            call ieee_get_halting_mode(ieee_overflow, halt)
            if (halt) call ieee_set_halting_mode(ieee_overflow, .false.)
            read (tok, *, iostat=ios) x(k)
            call ieee_set_flag(ieee_overflow, .false.)
            if (halt) call ieee_set_halting_mode(ieee_overflow, .true.)
            ! (ieee_is_finite: an ordered comparison with a NaN would trap in Debug builds)
            if (ios == 0) then
               if (.not. ieee_is_finite(x(k))) then
                  ! NaN, Inf, or out of range: every real read from a file is finite
                  call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'//short(tok)// &
                                  '": not a finite number', file=t%path, line=il)
                  ok = .false.
               else if (abs(x(k)) > MAX_COORDINATE) then
                  call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'//short(tok)// &
                                  '": beyond '//rtoa(MAX_COORDINATE)//' in magnitude (the geometry squares '// &
                                  'lengths)', file=t%path, line=il)
                  ok = .false.
               end if
               if (.not. ok) then
                  x(k) = 0.0_dp
                  return
               end if
            end if
         end associate
         if (ios /= 0) then
            call errors%add('E-GMSH', '$'//section//': expected '//what//', found "'// &
                            line(b(1, first + k - 1):b(2, first + k - 1))//'" where a number belongs', &
                            file=t%path, line=il)
            ok = .false.
            return
         end if
      end do
   end subroutine line_reals

   !> The closing $End<section> line.
   subroutine expect_end(t, section, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section
      type(error_list_t), intent(inout) :: errors
      logical, intent(inout) :: ok
      integer :: il
      if (.not. ok) return
      il = next_line(t)
      if (il == 0) then
         call errors%add('E-GMSH', 'truncated file: $End'//section//' is missing', file=t%path, line=t%nlines)
         ok = .false.
      else if (trim(adjustl(get_line(t, il))) /= '$End'//section) then
         call errors%add('E-GMSH', '$'//section//': expected $End'//section//' after the declared number of '// &
                         'entries, found "'//short(trim(get_line(t, il)))//'"', file=t%path, line=il)
         ok = .false.
      end if
   end subroutine expect_end

   !> Skip a section that Kontakt2D does not use.
   subroutine skip_section(t, section, errors, ok)
      type(msh_text_t), intent(inout) :: t
      character(len=*), intent(in) :: section
      type(error_list_t), intent(inout) :: errors
      logical, intent(out) :: ok
      integer :: il, il0
      il0 = t%pos
      ok = .true.
      do
         il = next_line(t)
         if (il == 0) then
            call errors%add('E-GMSH', 'truncated file: section $'//section//' has no $End'//section, &
                            file=t%path, line=il0)
            ok = .false.
            return
         end if
         if (trim(adjustl(get_line(t, il))) == '$End'//section) return
      end do
   end subroutine skip_section

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
         call errors%add('E-GMSH', 'truncated file: it ends inside $MeshFormat', file=t%path, line=t%nlines)
         return
      end if
      line = get_line(t, il)
      call tokens(line, b, nt)
      if (nt /= 3) then
         call errors%add('E-GMSH', '$MeshFormat: expected "version file-type data-size" (e.g. "4.1 0 8"), found "'// &
                         short(trim(line))//'"', file=t%path, line=il)
         return
      end if
      ver = line(b(1, 1):b(2, 1))
      ftype = line(b(1, 2):b(2, 2))
      if (ftype /= '0') then
         call errors%add('E-GMSH', 'binary .msh files are not supported (file-type '//ftype// &
                         '): save the mesh as ASCII, e.g. gmsh -2 -format msh41 file.geo, or with '// &
                         'Mesh.Binary = 0', file=t%path, line=il)
         return
      end if
      if (ver == '4.1' .or. ver == '4.10') then
         msh%version = '4.1'
      else if (ver == '2.2' .or. ver == '2.20') then
         msh%version = '2.2'
      else
         call errors%add('E-GMSH', 'unsupported .msh format version '//ver//': expected 4.1 or 2.2 (ASCII); '// &
                         'export with gmsh -format msh41 or msh22', file=t%path, line=il)
         return
      end if
      if (line(b(1, 3):b(2, 3)) /= '8') then
         call errors%add('E-GMSH', '$MeshFormat: data-size '//line(b(1, 3):b(2, 3))//' is not supported '// &
                         '(expected 8)', file=t%path, line=il)
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
         call read_ints(t, 'PhysicalNames', 'a line "dimension tag ""name"""', 2, v, errors, ok, il, at_least=.true.)
         if (.not. ok) return
         line = get_line(t, il)
         q1 = index(line, '"')
         q2 = index(line, '"', back=.true.)
         if (q1 == 0 .or. q2 <= q1) then
            call errors%add('E-GMSH', '$PhysicalNames: expected a quoted name after dimension and tag, found "'// &
                            short(trim(line))//'"', file=t%path, line=il)
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
      call read_ints(t, 'Entities', 'numPoints numCurves numSurfaces numVolumes', 4, v, errors, ok, il)
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
               call errors%add('E-GMSH', 'truncated file: it ends inside $Entities', file=t%path, line=t%nlines)
               ok = .false.
               return
            end if
            line = get_line(t, il)
            call tokens(line, b, nt)
            ! point: tag x y z nphys tags...; others: tag 6 bounds nphys tags... nbound tags...
            first = merge(5, 8, dim == 0)
            if (nt < first) then
               call errors%add('E-GMSH', '$Entities: expected an entity of dimension '//itoa(dim)// &
                               ', found "'//short(trim(line))//'"', file=t%path, line=il)
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
               call errors%add('E-GMSH', '$Entities: an entity belongs to '//itoa(nphys)//' physical groups; '// &
                               'at most '//itoa(MAX_PHYS)//' are supported', file=t%path, line=il)
               ok = .false.
               return
            end if
            ents(k, dim)%nphys = nphys
            do j = 1, nphys
               read (line(b(1, first + j):b(2, first + j)), *, iostat=ios) ents(k, dim)%phys(j)
               if (ios /= 0) then
                  call errors%add('E-GMSH', '$Entities: physical tag '//itoa(j)//' of entity '// &
                                  itoa(ents(k, dim)%tag)//': expected an integer, found "'// &
                                  short(line(b(1, first + j):b(2, first + j)))//'"', file=t%path, line=il)
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
      call read_ints(t, 'Nodes', 'numEntityBlocks numNodes minNodeTag maxNodeTag', 4, v, errors, ok, il)
      call check_count(t, 'Nodes', 'entity blocks', v(1), 1, il, errors, ok)
      call check_count(t, 'Nodes', 'nodes', v(2), 2, il, errors, ok)
      if (.not. ok) return
      nblk = v(1)
      call alloc_nodes(msh, v(2))
      n = 0
      do ib = 1, nblk
         call read_ints(t, 'Nodes', 'an entity block header "entityDim entityTag parametric numNodesInBlock"', &
                        4, v, errors, ok, il)
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
            call errors%add('E-GMSH', '$Nodes: the blocks hold more nodes than the '//itoa(msh%nnodes)// &
                            ' declared', file=t%path, line=il)
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
            call line_reals(t, il, 'Nodes', 'node coordinates "x y z"', 1, 3, msh%xyz(:, n + k), errors, ok)
            if (.not. ok) return
            msh%node_line(n + k) = il
         end do
         n = n + nin
      end do
      if (n /= msh%nnodes) then
         call errors%add('E-GMSH', '$Nodes: '//itoa(msh%nnodes)//' nodes declared, the blocks hold '//itoa(n), &
                         file=t%path, line=il)
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
         call read_ints(t, 'Nodes', 'a node line "tag x y z"', 1, v, errors, ok, il, at_least=.true.)
         if (.not. ok) return
         msh%node_tag(k) = v(1)
         call line_reals(t, il, 'Nodes', 'a node line "tag x y z"', 2, 3, msh%xyz(:, k), errors, ok)
         if (.not. ok) return
         msh%node_line(k) = il
      end do
      call expect_end(t, 'Nodes', errors, ok)
   end subroutine read_nodes22

   subroutine alloc_nodes(msh, n)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: n
      if (allocated(msh%node_tag)) deallocate (msh%node_tag, msh%xyz, msh%node_line)
      msh%nnodes = max(n, 0)
      allocate (msh%node_tag(msh%nnodes), msh%xyz(3, msh%nnodes), msh%node_line(msh%nnodes))
      msh%node_tag = 0
      msh%xyz = 0.0_dp
      msh%node_line = 0
   end subroutine alloc_nodes

   subroutine alloc_elements(msh, n)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: n
      msh%nelems = max(n, 0)
      allocate (msh%etype(msh%nelems), msh%enodes(MAX_NODE, msh%nelems), msh%nphys(msh%nelems), &
                msh%ephys(MAX_PHYS, msh%nelems), msh%eline(msh%nelems))
      msh%etype = 0
      msh%enodes = 0
      msh%nphys = 0
      msh%ephys = 0
      msh%eline = 0
   end subroutine alloc_elements

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
      call read_ints(t, 'Elements', 'numEntityBlocks numElements minElementTag maxElementTag', 4, v, errors, ok, il)
      call check_count(t, 'Elements', 'entity blocks', v(1), 1, il, errors, ok)
      call check_count(t, 'Elements', 'elements', v(2), 1, il, errors, ok)
      if (.not. ok) return
      nblk = v(1)
      call alloc_elements(msh, v(2))
      n = 0
      do ib = 1, nblk
         call read_ints(t, 'Elements', 'an entity block header "entityDim entityTag elementType '// &
                        'numElementsInBlock"', 4, v, errors, ok, il)
         if (.not. ok) return
         edim = v(1)
         etag = v(2)
         ety = v(3)
         nin = v(4)
         call check_count(t, 'Elements', 'elements in the block', nin, 1, il, errors, ok)
         if (.not. ok) return
         nn = gmsh_nnode(ety)
         if (nn == 0) then
            call errors%add('E-GMSH', 'unsupported element type '//itoa(ety)//' ('//type_name(ety)// &
                            '): Kontakt2D takes 3-node triangles, 4-, 8- and 9-node quadrilaterals, and '// &
                            'points and 2- or 3-node lines for physical groups', file=t%path, line=il)
            ok = .false.
            return
         end if
         if (n + nin > msh%nelems) then
            call errors%add('E-GMSH', '$Elements: the blocks hold more elements than the '//itoa(msh%nelems)// &
                            ' declared', file=t%path, line=il)
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
            call read_ints(t, 'Elements', 'an element line "tag node1 ... node'//itoa(nn)//'" of type '// &
                           itoa(ety), 1 + nn, v, errors, ok, il)
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
         call errors%add('E-GMSH', '$Elements: '//itoa(msh%nelems)//' elements declared, the blocks hold '//itoa(n), &
                         file=t%path, line=il)
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
         call read_ints(t, 'Elements', 'an element line "tag type ntags tags... nodes..."', 3, v, errors, ok, il, &
                        at_least=.true.)
         if (.not. ok) return
         ety = v(2)
         ntags = v(3)
         nn = gmsh_nnode(ety)
         if (nn == 0) then
            call errors%add('E-GMSH', 'unsupported element type '//itoa(ety)//' ('//type_name(ety)// &
                            '): Kontakt2D takes 3-node triangles, 4-, 8- and 9-node quadrilaterals, and '// &
                            'points and 2- or 3-node lines for physical groups', file=t%path, line=il)
            ok = .false.
            return
         end if
         if (ntags < 0 .or. ntags > 16) then
            call errors%add('E-GMSH', '$Elements: invalid number of tags '//itoa(ntags), file=t%path, line=il)
            ok = .false.
            return
         end if
         t%pos = t%pos - 1
         call read_ints(t, 'Elements', 'an element line with '//itoa(ntags)//' tags and '//itoa(nn)// &
                        ' nodes', 3 + ntags + nn, v, errors, ok, il)
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

   !> Groups used by elements but absent from $PhysicalNames get their tag as name.
   subroutine complete_groups(msh)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer :: k, j, dim
      logical :: found
      do k = 1, msh%nelems
         dim = gmsh_dim(msh%etype(k))
         do j = 1, msh%nphys(k)
            found = find_group(msh, dim, msh%ephys(j, k)) > 0
            if (.not. found) call add_group(msh, dim, msh%ephys(j, k), itoa(msh%ephys(j, k)))
         end do
      end do
   end subroutine complete_groups

   !> Append a physical group (component by component, see build_sets).
   subroutine add_group(msh, dim, tag, name)
      type(gmsh_mesh_t), intent(inout) :: msh
      integer, intent(in) :: dim, tag
      character(len=*), intent(in) :: name
      type(gmsh_group_t), allocatable :: tg(:)
      integer :: i
      allocate (tg(size(msh%groups) + 1))
      do i = 1, size(msh%groups)
         tg(i)%dim = msh%groups(i)%dim
         tg(i)%tag = msh%groups(i)%tag
         tg(i)%name = msh%groups(i)%name
      end do
      tg(size(tg))%dim = dim
      tg(size(tg))%tag = tag
      tg(size(tg))%name = name
      call move_alloc(tg, msh%groups)
   end subroutine add_group

   pure integer function find_group(msh, dim, tag) result(k)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim, tag
      do k = 1, size(msh%groups)
         if (msh%groups(k)%dim == dim .and. msh%groups(k)%tag == tag) return
      end do
      k = 0
   end function find_group

   !> Nodes of a gmsh element type that Kontakt2D takes (0 for any other).
   pure integer function gmsh_nnode(ety)
      integer, intent(in) :: ety
      select case (ety)
      case (15)
         gmsh_nnode = 1      ! point
      case (1)
         gmsh_nnode = 2      ! 2-node line
      case (8)
         gmsh_nnode = 3      ! 3-node line
      case (2)
         gmsh_nnode = 3      ! 3-node triangle
      case (3)
         gmsh_nnode = 4      ! 4-node quadrangle
      case (16)
         gmsh_nnode = 8      ! 8-node quadrangle
      case (10)
         gmsh_nnode = 9      ! 9-node quadrangle
      case default
         gmsh_nnode = 0
      end select
   end function gmsh_nnode

   pure integer function gmsh_dim(ety)
      integer, intent(in) :: ety
      select case (ety)
      case (15)
         gmsh_dim = 0
      case (1, 8)
         gmsh_dim = 1
      case default
         gmsh_dim = 2
      end select
   end function gmsh_dim

   pure function type_name(ety) result(s)
      integer, intent(in) :: ety
      character(len=:), allocatable :: s
      select case (ety)
      case (9)
         s = '6-node triangle: not in the element library; use 8- or 9-node quadrilaterals '// &
             '(Mesh.RecombineAll = 1) or 3-node triangles'
      case (4, 5, 6, 7, 11, 12, 13, 14, 17, 18, 19)
         s = 'a 3-D element'
      case (20:31)
         s = 'a higher-order element'
      case default
         s = 'not supported'
      end select
   end function type_name

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
         if (g == 0) call errors%add('E-GMSH', 'MESH: MATERIAL names physical surface "'//trim(mat_names(k))// &
                                     '", which '//msh%path//' does not have (its physical surfaces: '// &
                                     group_list(msh, 2)//')', file=deck_file, line=mat_lines(k), col=11)
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
                            ' on the control card requires '//itoa(nnode_req)//'-node elements only', &
                            file=msh%path, line=msh%eline(k))
            exit
         end if
      end do
      surf = surf(1:nsurf)
      ok = nsurf > 0
      if (.not. ok) then
         call errors%add('E-GMSH', 'the mesh has no 2-D elements (triangles or quadrilaterals): '// &
                         'mesh the surfaces (gmsh -2) and put them in physical surfaces', file=msh%path)
         return
      end if
      if (nq > 0 .and. nl > 0) then
         call errors%add('E-GMSH', 'the mesh mixes linear (3-, 4-node) and quadratic (8-, 9-node) elements, '// &
                         'which do not conform along their common edges', file=msh%path)
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
            call errors%add('E-GMSH', 'element of no physical surface: every surface must belong to a '// &
                            'physical surface named on a MATERIAL card', file=msh%path, line=msh%eline(k))
            exit
         end if
         do j = 1, msh%nphys(k)
            g = find_group(msh, 2, msh%ephys(j, k))
            kg = 0
            if (g > 0) kg = name_index(mat_names, msh%groups(g)%name)
            if (kg > 0) then
               if (imat /= 0 .and. imat /= mat_numbers(kg)) then
                  call errors%add('E-GMSH', 'element in two physical surfaces with different materials', &
                                  file=msh%path, line=msh%eline(k))
               end if
               imat = mat_numbers(kg)
            end if
         end do
         if (imat == 0) then
            g = find_group(msh, 2, msh%ephys(1, k))
            if (g > 0) then
               if (.not. unmapped_reported(g)) then
                  unmapped_reported(g) = .true.
                  call errors%add('E-GMSH', 'physical surface "'//msh%groups(g)%name//'" has no MATERIAL card '// &
                                  'in the MESH block of '//deck_file, file=msh%path, line=msh%eline(k))
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
                            file=msh%path, line=max(msh%node_line(perm(k)), msh%node_line(perm(k - 1))))
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
      allocate (m%coord(2, npoin), m%node_tag(npoin), m%node_line(npoin), m%lnods(MAX_NODE, nelem), &
                m%nnode_e(nelem), m%elem_line(nelem))
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
                  call errors%add('E-GMSH', 'physical group "'//grp%name//'": node tag '//itoa(tag)// &
                                  ' belongs to no 2-D element of the mesh', file=msh%path, line=msh%eline(k))
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
               call errors%add('E-GMSH', 'physical curve "'//grp%name//'": line element is not an '// &
                               'edge of any 2-D element', file=msh%path, line=msh%eline(k))
               return
            end if
            nsel = nsel + 1
            sel(nsel) = ie2
            sed(nsel) = iedge
         end do
         call add_sets(m, grp%name, pack([(q, q=1, m%npoin)], inset), grp%dim == 1, sel(1:nsel), sed(1:nsel))
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

   !> Index of the physical group of dimension dim called `name` (case-insensitive).
   integer function group_by_name(msh, dim, name) result(g)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim
      character(len=*), intent(in) :: name
      do g = 1, size(msh%groups)
         if (msh%groups(g)%dim == dim .and. same_name(msh%groups(g)%name, name)) return
      end do
      g = 0
   end function group_by_name

   !> Names of the physical groups of one dimension, quoted, for messages.
   function group_list(msh, dim) result(s)
      type(gmsh_mesh_t), intent(in) :: msh
      integer, intent(in) :: dim
      character(len=:), allocatable :: s
      integer :: g
      s = ''
      do g = 1, size(msh%groups)
         if (msh%groups(g)%dim /= dim) cycle
         if (len(s) > 0) s = s//', '
         s = s//'"'//msh%groups(g)%name//'"'
      end do
      if (len(s) == 0) s = 'none'
   end function group_list

end module gmsh_reader
