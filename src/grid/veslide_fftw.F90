!> Two-dimensional real FFTs through FFTW 3's Fortran 2003 interface, serial or distributed.
!>
!> One `fft2d_t` owns FFTW-aligned buffers `x` (nx, ny) and `k` (nx/2+1, ny) and the plans
!> between them, made once and reused. `forward` is x -> k, `backward` is k -> x divided by nx*ny,
!> so backward(forward(x)) = x. Never assign an `fft2d_t`: the copy would share, then free, C memory.
!>
!> On one process a 2-D transform is done as FFTW's 1-D transforms of blocks of `block` rows
!> (r2c / c2r along x) and of `block` spectral columns (c2c along y, in place), the blocks handed
!> to the OpenMP threads one at a time as they become free (schedule dynamic). The blocks are fixed
!> by the grid, not by the threads, so the arithmetic, and every bit of the result, is the same
!> for any number of threads; and a thread slowed by another process on its core holds up one
!> block, not half of the transform. (Measured on one thread: as fast as FFTW's 2-D plan, 0.86-1.01
!> of its time from 512^2 to 2048^2; docs/solver-scaling.md.)
!>
!> On a distributed grid (`distribute_grid`, the MPI build) the transforms are FFTW's MPI ones:
!> `x` holds the process's rows (nx, ny_local) and `k` its half-spectrum rows in FFTW's transposed
!> layout (ny, nq_local), so a Fourier multiplier costs one global transpose per transform; the
!> transforms run in place in a padded buffer of their own, `x` is copied in and out of it.
!>
!> Plans measured by FFTW (planner 'measure' or 'patient') are chosen by timing, which varies
!> from run to run; the machine's wisdom file (veslide_wisdom.c) keeps the first choice, so every
!> later run of a grid makes the same plan and repeats its results bit for bit.
module veslide_fftw
    use, intrinsic :: iso_c_binding
    use veslide_error, only: error_t, fatal_error
    use veslide_strings, only: c_strlen
    use veslide_grid, only: grid_t
    use veslide_clock, only: wall_seconds
#ifdef VESLIDE_MPI
    use mpi_f08, only: MPI_Comm, MPI_Comm_rank, MPI_Comm_size, MPI_Allgather, MPI_INTEGER
#endif
    use veslide_threads, only: threaded
    implicit none
    private
#ifdef VESLIDE_MPI
#include "fftw3-mpi.f03"
#else
#include "fftw3.f03"
#endif
    public :: fft2d_t, fft_planner_flag, fft_planner_names, distribute_grid

    !> rows (spectral columns) per FFTW call on one process: fixed, so the results do not depend on
    !> the threads (16: the fastest of 8, 16, 32 at 512^2-2048^2 on one thread)
    integer, parameter :: block = 16

    !> FFTW planner rigour by name (the namelist's `&solver fft_planner`)
    character(len=*), parameter :: fft_planner_names(3) = [character(len=8) :: 'estimate', 'measure', 'patient']

    type :: fft2d_t
        integer :: nx = 0, ny = 0
        logical :: distributed = .false.       !! FFTW's MPI transforms on a distributed grid
        real(c_double) :: seconds = 0.0_c_double  !! wall time spent in the transforms so far [s]
        integer :: transforms = 0              !! transforms executed so far
        type(c_ptr), private :: plan_r2c = c_null_ptr, plan_c2r = c_null_ptr  !! distributed: FFTW-MPI's
        !> one process: 1-D plans for a full block (1) and for the last, shorter one (2)
        type(c_ptr), private :: rows_r2c(2) = c_null_ptr, rows_c2r(2) = c_null_ptr
        type(c_ptr), private :: cols_fwd(2) = c_null_ptr, cols_bwd(2) = c_null_ptr
        type(c_ptr), private :: p_x = c_null_ptr, p_k = c_null_ptr
        !> real-space buffer, (nx, ny) (distributed: (nx, ny_local)), FFTW-aligned
        real(c_double), pointer, contiguous :: x(:, :) => null()
        !> half-spectrum buffer, (nx/2+1, ny) (distributed: (ny, nq_local)), FFTW-aligned
        complex(c_double_complex), pointer, contiguous :: k(:, :) => null()
        !> distributed: the padded real view (2 (nx/2+1), ny_local) of the in-place buffer
        real(c_double), pointer, private :: xr(:, :) => null()
    contains
        procedure :: init => fft_init
        procedure :: forward => fft_forward
        procedure :: backward => fft_backward
        procedure :: backward_unscaled => fft_backward_unscaled
        procedure :: destroy => fft_destroy
        final :: fft_finalize
    end type fft2d_t

    logical, save :: mpi_ready = .false.
    !> the wisdom file this process imported: -1 none yet, 0 the serial one, 1 the MPI one
    integer(c_int), save :: wisdom_loaded = -1

    interface
        subroutine c_free(p) bind(c, name='free')
            import :: c_ptr
            type(c_ptr), value :: p
        end subroutine c_free
        !> the machine's FFTW wisdom file (veslide_wisdom.c)
        !> (`mpi` 1: the file of a process with FFTW's MPI planners, whose wisdom holds MPI plans)
        integer(c_int) function wisdom_load(mpi) bind(c, name='veslide_wisdom_load')
            import :: c_int
            integer(c_int), value :: mpi
        end function wisdom_load
        integer(c_int) function wisdom_save(mpi) bind(c, name='veslide_wisdom_save')
            import :: c_int
            integer(c_int), value :: mpi
        end function wisdom_save
    end interface

contains

    !> Which wisdom file this process reads and writes: 1 once FFTW's MPI planners are registered
    !> (their plans in its wisdom), else 0 (veslide_wisdom.c)
    integer(c_int) function wisdom_kind() result(kind)
        kind = merge(1_c_int, 0_c_int, mpi_ready)
    end function wisdom_kind

    !> FFTW planner flag from its name: 'estimate', 'measure' or 'patient'
    integer function fft_planner_flag(name) result(flag)
        character(len=*), intent(in) :: name
        select case (name)
        case ('estimate'); flag = FFTW_ESTIMATE
        case ('patient'); flag = FFTW_PATIENT
        case default; flag = FFTW_MEASURE
        end select
    end function fft_planner_flag

    !> Allocate buffers and plan the transforms (buffers are overwritten by planning); with a
    !> distributed `grid`, FFTW's MPI transforms over its processes (collective).
    !> `isolated` plans FFTW_ESTIMATE without the process's accumulated wisdom (and leaves that
    !> wisdom as it was): a one-off transform whose rounding is the same in every run, whatever
    !> other plans the process made before (used by the surface generator).
    subroutine fft_init(self, nx, ny, error, planner, isolated, grid)
        class(fft2d_t), intent(inout) :: self
        !> grid size
        integer, intent(in) :: nx, ny
        !> error on failure
        type(error_t), allocatable, intent(out) :: error
        !> FFTW planner flag name (default 'measure')
        character(len=*), intent(in), optional :: planner
        !> plan FFTW_ESTIMATE, ignoring wisdom (default .false.)
        logical, intent(in), optional :: isolated
        !> the grid, when it may be distributed
        type(grid_t), intent(in), optional :: grid
        integer :: flag
        logical :: isolated_, planned
        type(c_ptr) :: saved
        integer(c_int) :: stat

        call self%destroy()
        if (nx < 1 .or. ny < 1) then
            call fatal_error(error, "veslide:fftw:init: grid size must be positive"); return
        end if
        if (present(grid)) then
            if (grid%is_distributed()) then
                call init_distributed(); return
            end if
        end if
        flag = FFTW_MEASURE
        if (present(planner)) flag = fft_planner_flag(planner)
        isolated_ = .false.; if (present(isolated)) isolated_ = isolated
        if (isolated_) flag = FFTW_ESTIMATE

        self%nx = nx; self%ny = ny
        self%p_x = fftw_alloc_real(int(nx, c_size_t)*int(ny, c_size_t))
        self%p_k = fftw_alloc_complex(int(nx/2 + 1, c_size_t)*int(ny, c_size_t))
        if (.not. (c_associated(self%p_x) .and. c_associated(self%p_k))) then
            call fatal_error(error, "veslide:fftw:init: cannot allocate FFT buffers"); return
        end if
        call c_f_pointer(self%p_x, self%x, [nx, ny])
        call c_f_pointer(self%p_k, self%k, [nx/2 + 1, ny])
        if (isolated_) then
            call set_wisdom_aside(saved)
        else if (flag /= FFTW_ESTIMATE .and. wisdom_loaded /= wisdom_kind()) then
            stat = wisdom_load(wisdom_kind()); wisdom_loaded = wisdom_kind()
        end if
        call plan_blocks(planned)
        if (isolated_) then
            call restore_wisdom(saved)
        else if (flag /= FFTW_ESTIMATE) then
            stat = wisdom_save(wisdom_kind())
        end if
        if (.not. planned) then
            call fatal_error(error, "veslide:fftw:init: FFTW returned a null plan"); return
        end if
        self%x = 0.0_c_double
        self%k = (0.0_c_double, 0.0_c_double)

    contains

        !> The 1-D plans of one process: r2c / c2r of `block` rows (x), c2c in place of `block`
        !> spectral columns (y; none when ny = 1), and the same for the last, shorter block. Each
        !> is planned on the buffer position of the block it runs on (FFTW requires the same
        !> alignment; every block starts a multiple of 16 rows or columns in, so all align alike).
        subroutine plan_blocks(ok)
            logical, intent(out) :: ok   !! no plan came back null
            integer :: nq, m, j0, count
            ok = .true.
            nq = nx/2 + 1
            do m = 1, 2
                call block_of_kind(m, ny, j0, count); if (count == 0) cycle
                self%rows_r2c(m) = fftw_plan_many_dft_r2c(1, [nx], count, self%x(:, j0:), [nx], 1, nx, &
                                                          self%k(:, j0:), [nq], 1, nq, flag)
                self%rows_c2r(m) = fftw_plan_many_dft_c2r(1, [nx], count, self%k(:, j0:), [nq], 1, nq, &
                                                          self%x(:, j0:), [nx], 1, nx, flag)
                ok = ok .and. c_associated(self%rows_r2c(m)) .and. c_associated(self%rows_c2r(m))
            end do
            if (ny == 1) return
            do m = 1, 2
                call block_of_kind(m, nq, j0, count); if (count == 0) cycle
                self%cols_fwd(m) = fftw_plan_many_dft(1, [ny], count, spectrum_from(self, j0), [ny], nq, 1, &
                                                      spectrum_from(self, j0), [ny], nq, 1, FFTW_FORWARD, flag)
                self%cols_bwd(m) = fftw_plan_many_dft(1, [ny], count, spectrum_from(self, j0), [ny], nq, 1, &
                                                      spectrum_from(self, j0), [ny], nq, 1, FFTW_BACKWARD, flag)
                ok = ok .and. c_associated(self%cols_fwd(m)) .and. c_associated(self%cols_bwd(m))
            end do
        end subroutine plan_blocks

        subroutine init_distributed()
#ifdef VESLIDE_MPI
            integer(c_intptr_t) :: alloc, ln0, l0s, ln1, l1s, n0, n1
            integer :: nq
            complex(c_double_complex), pointer :: kt(:, :)
            flag = FFTW_MEASURE
            if (present(planner)) flag = fft_planner_flag(planner)
            isolated_ = .false.; if (present(isolated)) isolated_ = isolated
            if (isolated_) flag = FFTW_ESTIMATE
            nq = nx/2 + 1
            n0 = ny; n1 = nq
            alloc = fftw_mpi_local_size_2d_transposed(n0, n1, int(grid%comm, c_int32_t), ln0, l0s, ln1, l1s)
            if (ln0 /= grid%ny_local .or. l0s /= grid%j0 .or. ln1 /= grid%nq_local .or. l1s /= grid%i0) then
                call fatal_error(error, "veslide:fftw:init: the grid was distributed for another communicator"); return
            end if
            self%distributed = .true.
            self%nx = nx; self%ny = ny
            self%p_k = fftw_alloc_complex(max(alloc, 1_c_intptr_t))
            self%p_x = fftw_alloc_real(max(1_c_size_t, int(nx, c_size_t)*int(ln0, c_size_t)))
            if (.not. (c_associated(self%p_x) .and. c_associated(self%p_k))) then
                call fatal_error(error, "veslide:fftw:init: cannot allocate FFT buffers"); return
            end if
            call c_f_pointer(self%p_x, self%x, [nx, int(ln0)])
            call c_f_pointer(self%p_k, self%xr, [2*nq, int(ln0)])
            call c_f_pointer(self%p_k, kt, [ny, int(ln1)])
            self%k => kt
            if (isolated_) then
                call set_wisdom_aside(saved)
            else if (flag /= FFTW_ESTIMATE) then
                ! the first process's file, shared so that every process plans alike
                if (grid%is_root() .and. wisdom_loaded /= 1) stat = wisdom_load(1_c_int)
                wisdom_loaded = 1
                call share_wisdom()
            end if
            call plan_mpi()
            if (isolated_) then
                call restore_wisdom(saved)
            else if (flag /= FFTW_ESTIMATE) then
                ! every process's part of the plan (their shares differ) gathered by the first and
                ! shared again, then planned anew from it: where a process measured a part that
                ! the first process had measured otherwise, it now takes the first's, as every
                ! later run (which reads the first's file) will, so the first run's bits are theirs
                call fftw_mpi_gather_wisdom(int(grid%comm, c_int32_t))
                call share_wisdom()
                call fftw_destroy_plan(self%plan_r2c); call fftw_destroy_plan(self%plan_c2r)
                call plan_mpi()
                if (grid%is_root()) stat = wisdom_save(1_c_int)
            end if
            if (.not. (c_associated(self%plan_r2c) .and. c_associated(self%plan_c2r))) then
                call fatal_error(error, "veslide:fftw:init: FFTW returned a null MPI plan"); return
            end if
            self%x = 0.0_c_double
            self%xr = 0.0_c_double
#else
            call fatal_error(error, "veslide:fftw:init: a distributed grid needs the MPI build (mpi/)")
#endif
        end subroutine init_distributed

#ifdef VESLIDE_MPI
        !> The first process's wisdom made every process's (importing adds to what a process
        !> has, where its own entries would win: the others forget theirs first)
        subroutine share_wisdom()
            if (.not. grid%is_root()) call fftw_forget_wisdom()
            call fftw_mpi_broadcast_wisdom(int(grid%comm, c_int32_t))
        end subroutine share_wisdom

        !> The MPI plans of the grid, transposed (collective)
        subroutine plan_mpi()
            complex(c_double_complex), pointer :: kt(:, :)
            call c_f_pointer(self%p_k, kt, [ny, grid%nq_local])
            self%plan_r2c = fftw_mpi_plan_dft_r2c_2d(int(ny, c_intptr_t), int(nx, c_intptr_t), self%xr, kt, &
                                                     int(grid%comm, c_int32_t), ior(flag, FFTW_MPI_TRANSPOSED_OUT))
            self%plan_c2r = fftw_mpi_plan_dft_c2r_2d(int(ny, c_intptr_t), int(nx, c_intptr_t), kt, self%xr, &
                                                     int(grid%comm, c_int32_t), ior(flag, FFTW_MPI_TRANSPOSED_IN))
        end subroutine plan_mpi
#endif

    end subroutine fft_init

    !> The process's wisdom kept aside as a string and forgotten (a plan made now ignores it)
    subroutine set_wisdom_aside(saved)
        type(c_ptr), intent(out) :: saved
        saved = fftw_export_wisdom_to_string()
        call fftw_forget_wisdom()
    end subroutine set_wisdom_aside

    !> The wisdom set aside restored, and what was planned meanwhile forgotten
    subroutine restore_wisdom(saved)
        type(c_ptr), intent(in) :: saved
        character(kind=c_char), pointer :: chars(:)
        integer(c_int) :: stat
        call fftw_forget_wisdom()
        if (c_associated(saved)) then
            call c_f_pointer(saved, chars, [c_strlen(saved) + 1])
            stat = fftw_import_wisdom_from_string(chars)
            call c_free(saved)
        end if
    end subroutine restore_wisdom

    !> Share `grid` among the processes of the MPI communicator `comm` (a Fortran handle), with
    !> FFTW's slab decomposition: rows of real fields, transposed half-spectrum rows (collective)
    subroutine distribute_grid(grid, comm, error)
        type(grid_t), intent(inout) :: grid
        integer, intent(in) :: comm
        type(error_t), allocatable, intent(out) :: error
#ifdef VESLIDE_MPI
        integer(c_intptr_t) :: alloc, ln0, l0s, ln1, l1s
        integer :: mine(2), ierr
        integer, allocatable :: all(:, :)
        type(MPI_Comm) :: c
        if (.not. mpi_ready) then
            call fftw_mpi_init()
            mpi_ready = .true.
        end if
        c%MPI_VAL = comm
        alloc = fftw_mpi_local_size_2d_transposed(int(grid%ny, c_intptr_t), int(grid%nx/2 + 1, c_intptr_t), &
                                                  int(comm, c_int32_t), ln0, l0s, ln1, l1s)
        grid%comm = comm
        call MPI_Comm_rank(c, grid%rank, ierr)
        call MPI_Comm_size(c, grid%ranks, ierr)
        grid%j0 = int(l0s); grid%ny_local = int(ln0)
        grid%transposed = .true.
        grid%i0 = int(l1s); grid%nq_local = int(ln1)
        mine = [grid%ny_local, grid%nq_local]
        allocate (all(2, grid%ranks))
        call MPI_Allgather(mine, 2, MPI_INTEGER, all, 2, MPI_INTEGER, c, ierr)
        grid%rows_of = all(1, :); grid%spectral_of = all(2, :)
        if (alloc < 0) call fatal_error(error, "veslide:fftw:distribute_grid: FFTW refused the grid")
#else
        call fatal_error(error, "veslide:fftw:distribute_grid: this build has no MPI (build mpi/ for distributed grids)")
#endif
    end subroutine distribute_grid

    !> x -> k (unnormalised forward transform, exp(-i q.x))
    subroutine fft_forward(self)
        class(fft2d_t), intent(inout) :: self
        real(c_double) :: t0
        t0 = wall_seconds()
        if (self%distributed) then
#ifdef VESLIDE_MPI
            self%xr(1:self%nx, :) = self%x
            call fftw_mpi_execute_dft_r2c(self%plan_r2c, self%xr, self%k)
#endif
        else
            call rows(self, forward=.true.)
            call columns(self, self%cols_fwd)
        end if
        self%seconds = self%seconds + (wall_seconds() - t0); self%transforms = self%transforms + 1
    end subroutine fft_forward

    !> k -> x, divided by nx*ny (the input k is destroyed, as FFTW's c2r does)
    subroutine fft_backward(self)
        class(fft2d_t), intent(inout) :: self
        call self%backward_unscaled()
        self%x = self%x/(real(self%nx, c_double)*real(self%ny, c_double))
    end subroutine fft_backward

    !> k -> x without the 1/(nx*ny) factor (for callers that fold it into a multiplier)
    subroutine fft_backward_unscaled(self)
        class(fft2d_t), intent(inout) :: self
        real(c_double) :: t0
        t0 = wall_seconds()
        if (self%distributed) then
#ifdef VESLIDE_MPI
            call fftw_mpi_execute_dft_c2r(self%plan_c2r, self%k, self%xr)
            self%x = self%xr(1:self%nx, :)
#endif
        else
            call columns(self, self%cols_bwd)
            call rows(self, forward=.false.)
        end if
        self%seconds = self%seconds + (wall_seconds() - t0); self%transforms = self%transforms + 1
    end subroutine fft_backward_unscaled

    !> Where the block of `kind` (1: a full block, 2: the last, shorter one) of `total` rows or
    !> spectral columns starts, and its length (0: there is none)
    pure subroutine block_of_kind(kind, total, first, count)
        integer, intent(in) :: kind, total
        integer, intent(out) :: first, count
        if (kind == 1) then
            first = 1; count = merge(block, 0, total >= block)
        else
            count = mod(total, block); first = total - count + 1
        end if
    end subroutine block_of_kind

    !> The kind of the block that starts at `first` of `total` (1 full, 2 the last, shorter)
    pure integer function plan_kind(first, total) result(kind)
        integer, intent(in) :: first, total
        kind = merge(1, 2, first + block - 1 <= total)
    end function plan_kind

    !> The half spectrum from spectral column i0 on, as one array (for FFTW's strided plans)
    function spectrum_from(self, i0) result(kc)
        class(fft2d_t), intent(in) :: self
        integer, intent(in) :: i0
        complex(c_double_complex), pointer, contiguous :: kc(:)
        call c_f_pointer(c_loc(self%k(i0, 1)), kc, [size(self%k) - (i0 - 1)])
    end function spectrum_from

    !> The rows' transforms, block by block: r2c (x -> k) when `forward`, else c2r (k -> x, k
    !> destroyed)
    subroutine rows(self, forward)
        class(fft2d_t), intent(inout) :: self
        logical, intent(in) :: forward
        integer :: b, j0, m
        !$omp parallel do schedule(dynamic) if (threaded(self%nx*self%ny, self%ny)) private(j0, m)
        do b = 1, (self%ny + block - 1)/block
            j0 = (b - 1)*block + 1
            m = plan_kind(j0, self%ny)
            if (forward) then
                call fftw_execute_dft_r2c(self%rows_r2c(m), self%x(:, j0:), self%k(:, j0:))
            else
                call fftw_execute_dft_c2r(self%rows_c2r(m), self%k(:, j0:), self%x(:, j0:))
            end if
        end do
        !$omp end parallel do
    end subroutine rows

    !> The spectral columns' c2c transforms in place, block by block, with `plans` (forward or
    !> backward; nothing to do when ny = 1)
    subroutine columns(self, plans)
        class(fft2d_t), intent(inout) :: self
        type(c_ptr), intent(in) :: plans(2)
        complex(c_double_complex), pointer, contiguous :: kc(:)
        integer :: b, i0, nq
        if (self%ny == 1) return
        nq = self%nx/2 + 1
        !$omp parallel do schedule(dynamic) if (threaded(self%nx*self%ny, self%ny)) private(i0, kc)
        do b = 1, (nq + block - 1)/block
            i0 = (b - 1)*block + 1
            kc => spectrum_from(self, i0)
            call fftw_execute_dft(plans(plan_kind(i0, nq)), kc, kc)
        end do
        !$omp end parallel do
    end subroutine columns

    !> Free plans and buffers
    subroutine fft_destroy(self)
        class(fft2d_t), intent(inout) :: self
        integer :: m
        if (c_associated(self%plan_r2c)) call fftw_destroy_plan(self%plan_r2c)
        if (c_associated(self%plan_c2r)) call fftw_destroy_plan(self%plan_c2r)
        do m = 1, 2
            if (c_associated(self%rows_r2c(m))) call fftw_destroy_plan(self%rows_r2c(m))
            if (c_associated(self%rows_c2r(m))) call fftw_destroy_plan(self%rows_c2r(m))
            if (c_associated(self%cols_fwd(m))) call fftw_destroy_plan(self%cols_fwd(m))
            if (c_associated(self%cols_bwd(m))) call fftw_destroy_plan(self%cols_bwd(m))
        end do
        self%rows_r2c = c_null_ptr; self%rows_c2r = c_null_ptr
        self%cols_fwd = c_null_ptr; self%cols_bwd = c_null_ptr
        if (c_associated(self%p_x)) call fftw_free(self%p_x)
        if (c_associated(self%p_k)) call fftw_free(self%p_k)
        self%plan_r2c = c_null_ptr; self%plan_c2r = c_null_ptr
        self%p_x = c_null_ptr; self%p_k = c_null_ptr
        nullify (self%x, self%k, self%xr)
        self%nx = 0; self%ny = 0; self%distributed = .false.
    end subroutine fft_destroy

    subroutine fft_finalize(self)
        type(fft2d_t), intent(inout) :: self
        call self%destroy()
    end subroutine fft_finalize

end module veslide_fftw
