!> The sphere solver's reusable memory (issue 32): the buffers a solve allocates at every
!> mesh, kept by the caller between solves so that the next solve's meshes reuse them
!> instead of fresh (page-faulting) memory. One workspace per thread, owned by whoever
!> runs the solves one after another (an unloading curve's unload_start): never shared.
module egw_solver_workspace
   use egw_kinds, only: dp
   use egw_halfspace, only: influence_cache
   implicit none
   private

   public :: solver_workspace, reserve

   !> What a solve reuses: the influence matrices its routes keep (each route clears the
   !> cache, clear_cache, and so starts as with a new one: the same coefficients, the same
   !> numbers) and the stiffness's Jacobian (differentiate). Buffers only grow.
   type :: solver_workspace
      type(influence_cache) :: cache
      !> differentiate's Jacobian, n x n in its first n**2 entries
      real(dp), allocatable :: jac(:)
   end type solver_workspace

contains

   !> buffer holds at least n entries afterwards (grown, its values dropped, only when it
   !> held fewer); stat: nonzero if it could not be allocated (buffer then unallocated).
   pure subroutine reserve(buffer, n, stat)
      real(dp), allocatable, intent(inout) :: buffer(:)   !< the buffer
      integer, intent(in) :: n   !< entries needed
      integer, intent(out) :: stat   !< 0, or the allocation's nonzero status
      stat = 0
      if (allocated(buffer)) then
         if (size(buffer) >= n) return
         deallocate (buffer)
      end if
      allocate (buffer(n), stat=stat)
   end subroutine reserve

end module egw_solver_workspace
