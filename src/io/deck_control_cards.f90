!> The TITLE, CONTROL and OPTIONS blocks of an input deck.
!!
!! Owns the title (at most MAX_TITLE characters), the control card (counts,
!! analysis type, element, Gauss rule and solver; the counts later blocks need
!! are kept in `control_t`) and the options (listing level, result interval,
!! renumbering, automatic increments, condensation).  Every field is checked
!! as docs/deck-format.md specifies, errors with file, line and column.
module deck_control_cards
   use kinds, only: dp
   use strings, only: itoa, rtoa
   use deck_lexer, only: deck_t
   use model, only: model_t
   use deck_blocks, only: is_block_card, next_data_card, skip_extra, check_tail
   implicit none
   private

   public :: control_t, MAX_TITLE, read_title, read_control, read_options

   !> Longest title (characters): it is one attribute of the result file.
   integer, parameter :: MAX_TITLE = 256

   !> Counts declared on the control card, needed by later blocks.
   type :: control_t
      integer :: nvfix = 0
      logical :: ok = .false.
      logical :: counts_from_mesh = .false.   !! NPOIN = NELEM = 0: a MESH block must give the mesh
      integer :: line = 0
   end type control_t

contains

   ! ------------------------------------------------------------------ TITLE

   subroutine read_title(d, ickw, m)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      integer :: ic
      if (d%at_end()) then
         call d%error_at(ickw, 1, 'E-TITLE', 'TITLE: expected a title card after the keyword, '// &
                         'found the end of the file')
         return
      end if
      ic = d%peek()
      if (is_block_card(d, ic)) then
         call d%error_at(ic, 1, 'E-TITLE', 'TITLE: expected a title card (one line of text), '// &
                         'found the block keyword '//d%keyword(ic))
         return
      end if
      ic = d%next()
      m%title = trim(adjustl(d%cards(ic)%text))
      if (len(m%title) > MAX_TITLE) then
         call d%error_at(ic, MAX_TITLE + 1, 'E-TITLE', 'TITLE: expected a title of at most '// &
                         itoa(MAX_TITLE)//' characters, found '//itoa(len(m%title)))
         m%title = m%title(1:MAX_TITLE)
      end if
      call skip_extra(d, 'TITLE')
   end subroutine read_title

   ! ------------------------------------------------------------------ CONTROL

   subroutine read_control(d, ickw, m, ctl)
      type(deck_t), intent(inout) :: d
      integer, intent(in) :: ickw
      type(model_t), intent(inout) :: m
      type(control_t), intent(inout) :: ctl
      integer :: ic
      logical :: ok
      character(len=:), allocatable :: w

      ic = next_data_card(d, 'CONTROL', 'the control card (NPOIN in columns 1-5)')
      if (ic == 0) then
         call d%error_at(ickw, 1, 'E-CONTROL', 'CONTROL: expected the control card '// &
                         '(NPOIN NELEM NVFIX NTYPE NNODE NMATS NGAUS SOLVER) after the keyword')
         return
      end if
      ctl%line = d%cards(ic)%line
      ok = .true.
      call d%get_int(ic, 1, 5, 'CONTROL', 'NPOIN', m%npoin, ok, default=0)
      call d%get_int(ic, 6, 10, 'CONTROL', 'NELEM', m%nelem, ok, default=0)
      call d%get_int(ic, 11, 15, 'CONTROL', 'NVFIX', ctl%nvfix, ok)
      call d%get_int(ic, 16, 20, 'CONTROL', 'NTYPE', m%ntype, ok)
      call d%get_int(ic, 21, 25, 'CONTROL', 'NNODE', m%nnode, ok, default=0)
      call d%get_int(ic, 26, 30, 'CONTROL', 'NMATS', m%nmats, ok)
      call d%get_int(ic, 31, 35, 'CONTROL', 'NGAUS', m%ngaus, ok, default=0)
      call d%get_word(ic, 36, 45, 'CONTROL', 'SOLVER', w, ok, default='AUTO')
      ctl%counts_from_mesh = ok .and. m%npoin == 0 .and. m%nelem == 0
      if (ok) then
         if (ctl%counts_from_mesh) then
            ! NPOIN = NELEM = 0: the mesh comes from a MESH block; NNODE 0 = any element of the file
            if (all(m%nnode /= [0, 3, 4, 8, 9])) call bad(21, 'NNODE (columns 21-25) expected '// &
                  '0 or blank (any element of the mesh file), 3, 4, 8 or 9, found '// &
                  itoa(m%nnode))
         else
            if (m%npoin < 1) call bad(1, 'NPOIN (columns 1-5) expected a positive number of '// &
                                      'nodes, found '//itoa(m%npoin))
            if (m%nelem < 1) call bad(6, 'NELEM (columns 6-10) expected a positive number of '// &
                                      'elements, found '//itoa(m%nelem))
            if (all(m%nnode /= [3, 4, 8, 9])) call bad(21, 'NNODE (columns 21-25) expected 3, '// &
                  '4, 8 or 9 nodes per element, found '//itoa(m%nnode))
         end if
         if (ctl%nvfix < 0) call bad(11, 'NVFIX (columns 11-15) expected a number of restraint '// &
                                     'cards >= 0, found '//itoa(ctl%nvfix))
         if (m%ntype < 1 .or. m%ntype > 3) call bad(16, 'NTYPE (columns 16-20) expected 1 '// &
               '(plane stress), 2 (plane strain) or 3 (axisymmetric), found '//itoa(m%ntype))
         if (m%nmats < 1) call bad(26, 'NMATS (columns 26-30) expected a positive number of '// &
                                   'materials, found '//itoa(m%nmats))
         if (m%ngaus < 0 .or. m%ngaus > 4) call bad(31, 'NGAUS (columns 31-35) expected 0 '// &
               '(default rule) or 1-4 Gauss points per direction, found '//itoa(m%ngaus))
         if (m%nnode == 3 .and. all(m%ngaus /= [0, 1, 3])) call bad(31, &
               'NGAUS (columns 31-35) for triangles expected 0, 1 or 3 points, found '// &
               itoa(m%ngaus))
         if (all(w /= [character(len=7) :: 'SKYLINE', 'UMFPACK', 'MUMPS', 'DENSE', 'AUTO'])) then
            call bad(36, 'SOLVER (columns 36-45) expected SKYLINE, UMFPACK, MUMPS, DENSE, AUTO '// &
                     'or blank (AUTO), found "'//w//'"')
         end if
      end if
      m%solver_name = w
      ctl%ok = ok
      call skip_extra(d, 'CONTROL')
   contains
      subroutine bad(col, msg)
         integer, intent(in) :: col
         character(len=*), intent(in) :: msg
         call d%error_at(ic, col, 'E-CONTROL', 'CONTROL: '//msg)
         ok = .false.
      end subroutine bad
   end subroutine read_control

   ! ------------------------------------------------------------------ OPTIONS

   subroutine read_options(d, m)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      integer :: ic
      logical :: ok
      real(dp) :: x
      integer :: iv
      character(len=:), allocatable :: key, val

      do while (.not. d%at_end())
         ic = d%peek()
         if (is_block_card(d, ic)) exit
         ic = d%next()
         ok = .true.
         call d%get_word(ic, 1, 10, 'OPTIONS', 'KEY', key, ok)
         if (.not. ok) cycle
         select case (key)
         case ('LISTING')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'LISTING', val, ok)
            if (ok .and. all(val /= [character(len=5) :: 'FULL', 'SHORT', 'NONE'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: LISTING (columns 11-20) expected '// &
                               'FULL, SHORT or NONE, found "'//val//'"')
            else if (ok) then
               m%listing_level = val
            end if
         case ('RENUMBER')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'RENUMBER', val, ok)
            if (ok .and. all(val /= [character(len=4) :: 'RCM', 'NONE'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: RENUMBER (columns 11-20) expected '// &
                               'RCM or NONE, found "'//val//'"')
            else if (ok) then
               m%renumber = val
            end if
         case ('AUTOINC')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'AUTOINC', val, ok)
            call d%get_real(ic, 21, 30, 'OPTIONS', 'MINFRAC', x, ok, default=1.0_dp/128.0_dp)
            call d%get_int(ic, 31, 40, 'OPTIONS', 'NEASY', iv, ok, default=4)
            call check_tail(d, ic, 41, 'OPTIONS/AUTOINC', &
                            'ON or OFF, MINFRAC, NEASY in columns 11-40', ok)
            if (ok .and. all(val /= [character(len=3) :: 'ON', 'OFF'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: AUTOINC (columns 11-20) expected '// &
                               'ON or OFF, found "'//val//'"')
            else if (ok .and. .not. (x > 0.0_dp .and. x <= 1.0_dp)) then
               call d%error_at(ic, 21, 'E-OPTION', 'OPTIONS: AUTOINC MINFRAC (columns 21-30) '// &
                               'expected the smallest step as a fraction of a deck increment, '// &
                               'in (0, 1], found '//rtoa(x))
            else if (ok .and. iv < 1) then
               call d%error_at(ic, 31, 'E-OPTION', 'OPTIONS: AUTOINC NEASY (columns 31-40) '// &
                               'expected a number of solutions >= 1, found '//itoa(iv))
            else if (ok) then
               m%autoinc = val == 'ON'
               m%autoinc_min = x
               m%autoinc_easy = iv
            end if
         case ('RESULTS')
            call d%get_int(ic, 11, 20, 'OPTIONS', 'RESULTS', iv, ok)
            call check_tail(d, ic, 21, 'OPTIONS/RESULTS', 'N in columns 11-20', ok)
            if (ok .and. iv < 1) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: RESULTS (columns 11-20) expected '// &
                               'the step interval of the result file, an integer >= 1, found '// &
                               itoa(iv))
            else if (ok) then
               m%results_every = iv
            end if
         case ('CONDENSE')
            call d%get_word(ic, 11, 20, 'OPTIONS', 'CONDENSE', val, ok)
            if (ok .and. all(val /= [character(len=4) :: 'AUTO', 'ON', 'OFF'])) then
               call d%error_at(ic, 11, 'E-OPTION', 'OPTIONS: CONDENSE (columns 11-20) expected '// &
                               'AUTO, ON or OFF, found "'//val//'"')
            else if (ok) then
               m%condense = val
            end if
         case default
            call d%error_at(ic, 1, 'E-OPTION', 'OPTIONS: unknown option "'//key// &
                            '" (columns 1-10); known: LISTING, RESULTS, RENUMBER, AUTOINC, '// &
                            'CONDENSE')
         end select
      end do
   end subroutine read_options

end module deck_control_cards
