!> Reader of the TIES block of a deck (docs/deck-format.md): cards CODE, N1 ... N15
!! (I5 fields) tying the listed nodes' x and/or y dofs to N1's.  Chains of ties are
!! resolved to one master per dof; a restrained dof or a node tied twice is an error
!! at the card (file:line, column of the node's field).
module deck_ties
   use strings, only: itoa
   use deck_lexer, only: deck_t
   use model, only: model_t
   implicit none
   private
   public :: read_ties

contains

   !> TIES: cards (CODE, N1, N2, ... N15): the listed nodes share N1's dofs.
   subroutine read_ties(d, m, is_block_card)
      type(deck_t), intent(inout) :: d
      type(model_t), intent(inout) :: m
      interface
         logical function is_block_card(d, ic)
            import :: deck_t
            type(deck_t), intent(in) :: d
            integer, intent(in) :: ic
         end function is_block_card
      end interface
      integer, allocatable :: ties(:, :), master_of(:, :)
      logical, allocatable :: restrained(:, :)
      integer :: ic, code, k, node, nt, idof, c1, master, nlist, list(15)
      logical :: ok

      allocate (ties(3, 16), master_of(2, m%npoin), restrained(2, m%npoin))
      master_of = 0
      restrained = .false.
      do k = 1, size(m%fixes)
         restrained(:, m%fixes(k)%node) = restrained(:, m%fixes(k)%node) .or. m%fixes(k)%fixed
      end do
      nt = 0
      do while (.not. d%at_end())
         if (is_block_card(d, d%peek())) exit
         ic = d%next()
         ok = .true.
         call d%get_int(ic, 1, 5, 'TIES', 'CODE', code, ok)
         nlist = 0
         do k = 1, 15
            c1 = 6 + 5*(k - 1)
            if (len_trim(d%field_text(ic, c1, c1 + 4)) == 0) cycle
            nlist = nlist + 1
            call d%get_int(ic, c1, c1 + 4, 'TIES', 'N'//itoa(k), list(nlist), ok)
         end do
         if (len_trim(d%field_text(ic, 81, 100000)) > 0) then
            call d%error_at(ic, 81, 'E-EXTRA', &
               'TIES: expected CODE and at most 15 node numbers in columns 1-80')
            ok = .false.
         end if
         if (.not. ok) cycle
         if (all(code /= [1, 10, 11])) then
            call d%error_at(ic, 1, 'E-CODE', &
               'TIES: CODE (columns 1-5) expected 10 (x), 01 (y) or 11 (both), found '// &
               itoa(code))
            cycle
         end if
         if (nlist < 2) then
            call d%error_at(ic, 6, 'E-TIE', &
               'TIES: expected at least two node numbers (the first is the master), found '// &
               itoa(nlist))
            cycle
         end if
         if (any(list(1:nlist) < 1 .or. list(1:nlist) > m%npoin)) then
            call d%error_at(ic, 6, 'E-RANGE', 'TIES: node numbers expected in 1..'//itoa(m%npoin))
            cycle
         end if
         do idof = 1, 2
            if (idof == 1 .and. code < 10) cycle
            if (idof == 2 .and. mod(code, 10) /= 1) cycle
            master = list(1)
            do while (master_of(idof, master) /= 0)
               master = master_of(idof, master)
            end do
            do k = 1, nlist
               node = list(k)
               if (restrained(idof, node)) then
                  call d%error_at(ic, 1 + 5*k, 'E-TIE', 'TIES: node '//itoa(node)// &
                     ' is restrained in '//merge('x', 'y', idof == 1)//'; ties act on free '// &
                     'dofs only')
                  cycle
               end if
               if (k == 1) cycle
               if (node == master) cycle
               if (master_of(idof, node) /= 0) then
                  call d%error_at(ic, 1 + 5*k, 'E-TIE', 'TIES: node '//itoa(node)// &
                     ' is tied twice in '//merge('x', 'y', idof == 1))
                  cycle
               end if
               master_of(idof, node) = master
               if (nt >= size(ties, 2)) ties = reshape([ties, ties], [3, 2*size(ties, 2)])
               nt = nt + 1
               ties(:, nt) = [master, node, idof]
            end do
         end do
      end do
      ! a master that became a slave later: point its slaves at the final master
      do k = 1, nt
         master = ties(1, k)
         do while (master_of(ties(3, k), master) /= 0)
            master = master_of(ties(3, k), master)
         end do
         ties(1, k) = master
      end do
      m%ties = ties(:, 1:nt)
   end subroutine read_ties
end module deck_ties
