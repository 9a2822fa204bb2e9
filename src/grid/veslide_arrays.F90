!> The arrays of a solve, held where the solve runs: on the host (the CPU backend) a Fortran
!> array, on the device (the GPU backend) device memory. A solver's control flow is written once
!> on these handles; each pass it calls (veslide_*_passes) looks at `device` and runs its CPU
!> twin on `h` or its CUDA twin on `d`.
!>
!> One handle per element kind: `rarray_t` real(dp), `carray_t` complex(dp) (a half-spectrum),
!> `iarray_t` int8 (a set of cells), `sarray_t` real32 (a single-precision history). On the
!> host a handle either owns its array (`create`) or views one the caller owns (`view`: the
!> caller's array must outlive the handle, and is neither copied nor freed). On the device it
!> always owns its memory; `upload` and `download` move the contents between the two.
module veslide_arrays
    use, intrinsic :: iso_c_binding, only: c_ptr, c_null_ptr, c_associated, c_long
    use, intrinsic :: iso_fortran_env, only: int8, real32
    use veslide_kinds, only: dp, i8
    use veslide_device, only: device_alloc, device_free, device_upload, device_download, device_copy
    implicit none
    private
    public :: rarray_t, carray_t, iarray_t, sarray_t, elements

    !> The number of elements of an array of a solve (as C's long: a kernel's count)
    interface elements
        module procedure r_elements, c_elements, i_elements
    end interface elements

    !> A real(dp) array (n1, n2)
    type :: rarray_t
        integer :: n1 = 0, n2 = 0
        logical :: device = .false.                           !! held on the device
        real(dp), pointer, contiguous :: h(:, :) => null()    !! host: the array
        type(c_ptr) :: d = c_null_ptr                          !! device: its memory
        integer(i8) :: bytes = 0                               !! device: the bytes held there
        logical, private :: owned = .false.
    contains
        procedure :: create => r_create
        procedure :: view => r_view
        procedure :: destroy => r_destroy
        procedure :: upload => r_upload
        procedure :: download => r_download
        procedure :: assign => r_assign
    end type rarray_t

    !> A complex(dp) array (n1, n2)
    type :: carray_t
        integer :: n1 = 0, n2 = 0
        logical :: device = .false.
        complex(dp), pointer, contiguous :: h(:, :) => null()
        type(c_ptr) :: d = c_null_ptr
        logical, private :: owned = .false.
    contains
        procedure :: create => c_create
        procedure :: view => c_view
        procedure :: destroy => c_destroy
        procedure :: upload => c_upload
        procedure :: download => c_download
        procedure :: assign => c_assign
    end type carray_t

    !> An int8 array (n1, n2)
    type :: iarray_t
        integer :: n1 = 0, n2 = 0
        logical :: device = .false.
        integer(int8), pointer, contiguous :: h(:, :) => null()
        type(c_ptr) :: d = c_null_ptr
        logical, private :: owned = .false.
    contains
        procedure :: create => i_create
        procedure :: destroy => i_destroy
    end type iarray_t

    !> A real32 array (n1, n2)
    type :: sarray_t
        integer :: n1 = 0, n2 = 0
        logical :: device = .false.
        real(real32), pointer, contiguous :: h(:, :) => null()
        type(c_ptr) :: d = c_null_ptr
        logical, private :: owned = .false.
    contains
        procedure :: create => s_create
        procedure :: destroy => s_destroy
    end type sarray_t

contains

    !> Bytes of n1 x n2 elements of `size` bytes
    pure integer(i8) function nbytes(n1, n2, size)
        integer, intent(in) :: n1, n2, size
        nbytes = int(n1, i8)*int(n2, i8)*size
    end function nbytes

    pure integer(c_long) function r_elements(a) result(n)
        type(rarray_t), intent(in) :: a
        n = int(a%n1, c_long)*int(a%n2, c_long)
    end function r_elements

    pure integer(c_long) function c_elements(a) result(n)
        type(carray_t), intent(in) :: a
        n = int(a%n1, c_long)*int(a%n2, c_long)
    end function c_elements

    pure integer(c_long) function i_elements(a) result(n)
        type(iarray_t), intent(in) :: a
        n = int(a%n1, c_long)*int(a%n2, c_long)
    end function i_elements

    ! ---- rarray_t ------------------------------------------------------------------------

    !> Storage of its own for (n1, n2), on the device or the host (contents undefined); on the
    !> device at least `at_least` bytes (a scratch area it also serves as: veslide_transform)
    subroutine r_create(self, n1, n2, device, at_least)
        class(rarray_t), intent(inout) :: self
        integer, intent(in) :: n1, n2
        logical, intent(in) :: device
        integer(i8), intent(in), optional :: at_least
        call self%destroy()
        self%n1 = n1; self%n2 = n2; self%device = device
        if (device) then
            self%bytes = nbytes(n1, n2, 8)
            if (present(at_least)) self%bytes = max(self%bytes, at_least)
            call device_alloc(self%d, self%bytes)
        else
            allocate (self%h(n1, n2)); self%owned = .true.
        end if
    end subroutine r_create

    !> A host view of the caller's array `a` (no copy)
    subroutine r_view(self, a)
        class(rarray_t), intent(inout) :: self
        real(dp), intent(in), target, contiguous :: a(:, :)
        call self%destroy()
        self%n1 = size(a, 1); self%n2 = size(a, 2); self%device = .false.
        self%h => a
    end subroutine r_view

    subroutine r_destroy(self)
        class(rarray_t), intent(inout) :: self
        if (self%owned .and. associated(self%h)) deallocate (self%h)
        nullify (self%h); self%owned = .false.
        if (c_associated(self%d)) call device_free(self%d)
        self%d = c_null_ptr; self%bytes = 0
        self%n1 = 0; self%n2 = 0
    end subroutine r_destroy

    !> The contents set from the host array `a` (its shape)
    subroutine r_upload(self, a)
        class(rarray_t), intent(inout) :: self
        real(dp), intent(in), contiguous :: a(:, :)
        if (self%device) then
            call device_upload(self%d, a, nbytes(self%n1, self%n2, 8))
        else
            self%h = a
        end if
    end subroutine r_upload

    !> The contents into the host array `a` (its shape)
    subroutine r_download(self, a)
        class(rarray_t), intent(in) :: self
        real(dp), intent(inout), contiguous :: a(:, :)
        if (self%device) then
            call device_download(a, self%d, nbytes(self%n1, self%n2, 8))
        else
            a = self%h
        end if
    end subroutine r_download

    !> The contents set from another array of the same shape, where both are
    subroutine r_assign(self, other)
        class(rarray_t), intent(inout) :: self
        type(rarray_t), intent(in) :: other
        if (self%device) then
            call device_copy(self%d, other%d, nbytes(self%n1, self%n2, 8))
        else
            self%h = other%h
        end if
    end subroutine r_assign

    ! ---- carray_t ------------------------------------------------------------------------

    subroutine c_create(self, n1, n2, device)
        class(carray_t), intent(inout) :: self
        integer, intent(in) :: n1, n2
        logical, intent(in) :: device
        call self%destroy()
        self%n1 = n1; self%n2 = n2; self%device = device
        if (device) then
            call device_alloc(self%d, nbytes(n1, n2, 16))
        else
            allocate (self%h(n1, n2)); self%owned = .true.
        end if
    end subroutine c_create

    subroutine c_view(self, a)
        class(carray_t), intent(inout) :: self
        complex(dp), intent(in), target, contiguous :: a(:, :)
        call self%destroy()
        self%n1 = size(a, 1); self%n2 = size(a, 2); self%device = .false.
        self%h => a
    end subroutine c_view

    subroutine c_destroy(self)
        class(carray_t), intent(inout) :: self
        if (self%owned .and. associated(self%h)) deallocate (self%h)
        nullify (self%h); self%owned = .false.
        if (c_associated(self%d)) call device_free(self%d)
        self%d = c_null_ptr
        self%n1 = 0; self%n2 = 0
    end subroutine c_destroy

    subroutine c_upload(self, a)
        class(carray_t), intent(inout) :: self
        complex(dp), intent(in), contiguous :: a(:, :)
        if (self%device) then
            call device_upload(self%d, a, nbytes(self%n1, self%n2, 16))
        else
            self%h = a
        end if
    end subroutine c_upload

    subroutine c_download(self, a)
        class(carray_t), intent(in) :: self
        complex(dp), intent(inout), contiguous :: a(:, :)
        if (self%device) then
            call device_download(a, self%d, nbytes(self%n1, self%n2, 16))
        else
            a = self%h
        end if
    end subroutine c_download

    subroutine c_assign(self, other)
        class(carray_t), intent(inout) :: self
        type(carray_t), intent(in) :: other
        if (self%device) then
            call device_copy(self%d, other%d, nbytes(self%n1, self%n2, 16))
        else
            self%h = other%h
        end if
    end subroutine c_assign

    ! ---- iarray_t, sarray_t --------------------------------------------------------------

    subroutine i_create(self, n1, n2, device)
        class(iarray_t), intent(inout) :: self
        integer, intent(in) :: n1, n2
        logical, intent(in) :: device
        call self%destroy()
        self%n1 = n1; self%n2 = n2; self%device = device
        if (device) then
            call device_alloc(self%d, nbytes(n1, n2, 1))
        else
            allocate (self%h(n1, n2)); self%owned = .true.
        end if
    end subroutine i_create

    subroutine i_destroy(self)
        class(iarray_t), intent(inout) :: self
        if (self%owned .and. associated(self%h)) deallocate (self%h)
        nullify (self%h); self%owned = .false.
        if (c_associated(self%d)) call device_free(self%d)
        self%d = c_null_ptr
        self%n1 = 0; self%n2 = 0
    end subroutine i_destroy

    subroutine s_create(self, n1, n2, device)
        class(sarray_t), intent(inout) :: self
        integer, intent(in) :: n1, n2
        logical, intent(in) :: device
        call self%destroy()
        self%n1 = n1; self%n2 = n2; self%device = device
        if (device) then
            call device_alloc(self%d, nbytes(n1, n2, 4))
        else
            allocate (self%h(n1, n2)); self%owned = .true.
        end if
    end subroutine s_create

    subroutine s_destroy(self)
        class(sarray_t), intent(inout) :: self
        if (self%owned .and. associated(self%h)) deallocate (self%h)
        nullify (self%h); self%owned = .false.
        if (c_associated(self%d)) call device_free(self%d)
        self%d = c_null_ptr
        self%n1 = 0; self%n2 = 0
    end subroutine s_destroy

end module veslide_arrays
