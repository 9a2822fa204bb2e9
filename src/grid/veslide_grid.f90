!> The periodic grid and the rules of its r2c half-spectrum, in one place.
!>
!> A field f(i, j), i = 1..nx, j = 1..ny, samples a periodic cell lx_m x ly_m at the points
!> ((i-1) lx_m/nx, (j-1) ly_m/ny). Its r2c transform is stored on the half-spectrum
!> (nx/2+1, ny): entry (i, j) is the wavenumber (ki, kj) = (i-1, j-1 wrapped to j-1-ny above ny/2),
!> wavevector q = 2 pi (ki/lx_m, kj/ly_m). Rules every spectral sum follows:
!>  - Hermitian weight: every stored entry stands for itself and its conjugate partner -q, except
!>    the ki = 0 column and, for even nx, the ki = nx/2 column, whose partners are stored themselves
!>    (weight 1 instead of 2);
!>  - Nyquist lines (ki = nx/2 for even nx > 1, kj = ny/2 for even ny > 1) carry no derivative:
!>    the sign of the wavenumber is undefined there, so d/dx (d/dy) gives zero on them;
!>  - the q = 0 mode is the mean.
!>
!> Distribution over processes (veslide_fftw's `distribute_grid`; a serial grid owns everything):
!> a process owns the rows j0+1 .. j0+ny_local of every real field, stored (nx, ny_local), and the
!> half-spectrum rows i0+1 .. i0+nq_local of every transform, stored transposed as (ny, nq_local)
!> (FFTW's MPI layout, which saves one global transpose per transform). `spectral_shape` and
!> `spectral_index` translate storage positions (a, b) to half-spectrum entries (i, j), so every
!> spectral loop is written once for both layouts. In both, storage (1, 1) is q = 0 where owned.
module veslide_grid
    use veslide_kinds, only: dp, two_pi
    use veslide_error, only: error_t, fatal_error
    implicit none
    private
    public :: grid_t, new_grid

    !> A periodic nx x ny grid on an lx_m x ly_m cell
    type :: grid_t
        integer :: nx = 0, ny = 0              !! points along x and y
        real(dp) :: lx_m = 0.0_dp, ly_m = 0.0_dp  !! cell side lengths [m]
        ! the share of this process
        integer :: comm = -1                   !! MPI communicator (Fortran handle); -1: not distributed
        integer :: rank = 0, ranks = 1         !! this process and the number of processes
        integer :: j0 = 0, ny_local = 0        !! real-space rows owned: j0+1 .. j0+ny_local
        logical :: transposed = .false.        !! spectral storage (ny, nq_local) instead of (nx/2+1, ny)
        integer :: i0 = 0, nq_local = 0        !! half-spectrum rows owned: i0+1 .. i0+nq_local
        integer, allocatable :: rows_of(:), spectral_of(:)  !! ny_local and nq_local of every rank
    contains
        procedure :: nq => grid_nq
        procedure :: cells => grid_cells
        procedure :: spacing => grid_spacing
        procedure :: wavenumber => grid_wavenumber
        procedure :: wavevector => grid_wavevector
        procedure :: derivative_wavevector => grid_derivative_wavevector
        procedure :: is_nyquist_x => grid_is_nyquist_x
        procedure :: is_nyquist_y => grid_is_nyquist_y
        procedure :: hermitian_weight => grid_hermitian_weight
        procedure :: q0 => grid_q0
        procedure :: local_shape => grid_local_shape
        procedure :: spectral_shape => grid_spectral_shape
        procedure :: spectral_index => grid_spectral_index
        procedure :: owns_mean_mode => grid_owns_mean_mode
        procedure :: is_distributed => grid_is_distributed
        procedure :: is_root => grid_is_root
    end type grid_t

contains

    !> A grid of nx x ny points on an lx_m x ly_m cell; sizes and lengths must be positive and finite
    subroutine new_grid(self, nx, ny, lx_m, ly_m, error)
        type(grid_t), intent(out) :: self
        integer, intent(in) :: nx, ny
        real(dp), intent(in) :: lx_m, ly_m
        type(error_t), allocatable, intent(out) :: error
        if (nx < 1 .or. ny < 1) then
            call fatal_error(error, "veslide:grid:new_grid: nx and ny must be positive"); return
        end if
        if (.not. (lx_m > 0.0_dp .and. lx_m < huge(1.0_dp) .and. ly_m > 0.0_dp .and. ly_m < huge(1.0_dp))) then
            call fatal_error(error, "veslide:grid:new_grid: lx_m and ly_m must be positive and finite"); return
        end if
        self%nx = nx; self%ny = ny; self%lx_m = lx_m; self%ly_m = ly_m
        self%j0 = 0; self%ny_local = ny; self%i0 = 0; self%nq_local = nx/2 + 1
        self%rows_of = [ny]; self%spectral_of = [nx/2 + 1]
    end subroutine new_grid

    !> Shape of a real field on this process, (nx, ny_local)
    pure function grid_local_shape(self) result(s)
        class(grid_t), intent(in) :: self
        integer :: s(2)
        s = [self%nx, self%ny_local]
    end function grid_local_shape

    !> Shape of a half-spectrum on this process: (nx/2+1, ny), or (ny, nq_local) when transposed
    pure function grid_spectral_shape(self) result(s)
        class(grid_t), intent(in) :: self
        integer :: s(2)
        if (self%transposed) then
            s = [self%ny, self%nq_local]
        else
            s = [self%nq(), self%ny]
        end if
    end function grid_spectral_shape

    !> Half-spectrum entry (i, j) of storage position (a, b) on this process
    pure function grid_spectral_index(self, a, b) result(ij)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: a, b
        integer :: ij(2)
        if (self%transposed) then
            ij = [self%i0 + b, a]
        else
            ij = [a, b]
        end if
    end function grid_spectral_index

    !> Does this process hold the q = 0 mode (at storage position (1, 1))?
    elemental logical function grid_owns_mean_mode(self) result(yes)
        class(grid_t), intent(in) :: self
        yes = self%i0 == 0 .and. self%nq_local > 0
    end function grid_owns_mean_mode

    !> Is the grid shared by several processes (an MPI communicator)?
    elemental logical function grid_is_distributed(self) result(yes)
        class(grid_t), intent(in) :: self
        yes = self%comm /= -1
    end function grid_is_distributed

    !> Is this the first process (the one that prints)?
    elemental logical function grid_is_root(self) result(yes)
        class(grid_t), intent(in) :: self
        yes = self%rank == 0
    end function grid_is_root

    !> Rows of the half-spectrum, nx/2 + 1
    elemental integer function grid_nq(self) result(n)
        class(grid_t), intent(in) :: self
        n = self%nx/2 + 1
    end function grid_nq

    !> Number of grid points, nx*ny, as a real (for means and the FFT normalisation)
    elemental real(dp) function grid_cells(self) result(n)
        class(grid_t), intent(in) :: self
        n = real(self%nx, dp)*real(self%ny, dp)
    end function grid_cells

    !> Point spacing (lx_m/nx, ly_m/ny) [m]
    pure function grid_spacing(self) result(d)
        class(grid_t), intent(in) :: self
        real(dp) :: d(2)
        d = [self%lx_m/self%nx, self%ly_m/self%ny]
    end function grid_spacing

    !> Fundamental wavenumber along x, 2 pi/lx_m [1/m]
    elemental real(dp) function grid_q0(self) result(q0)
        class(grid_t), intent(in) :: self
        q0 = two_pi/self%lx_m
    end function grid_q0

    !> Signed integer wavenumber (ki, kj) of half-spectrum entry (i, j)
    pure function grid_wavenumber(self, i, j) result(k)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: i, j
        integer :: k(2)
        k = [i - 1, j - 1]
        if (k(2) > self%ny/2) k(2) = k(2) - self%ny
    end function grid_wavenumber

    !> Wavevector q of half-spectrum entry (i, j) [1/m]
    pure function grid_wavevector(self, i, j) result(q)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: i, j
        real(dp) :: q(2)
        integer :: k(2)
        k = self%wavenumber(i, j)
        q = [two_pi*real(k(1), dp)/self%lx_m, two_pi*real(k(2), dp)/self%ly_m]
    end function grid_wavevector

    !> Wavevector of the spectral derivative at (i, j): q with its Nyquist components set to zero
    pure function grid_derivative_wavevector(self, i, j) result(q)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: i, j
        real(dp) :: q(2)
        q = self%wavevector(i, j)
        if (self%is_nyquist_x(i)) q(1) = 0.0_dp
        if (self%is_nyquist_y(j)) q(2) = 0.0_dp
    end function grid_derivative_wavevector

    !> Is row i of the half-spectrum the Nyquist line ki = nx/2 (even nx > 1)?
    elemental logical function grid_is_nyquist_x(self, i) result(yes)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: i
        yes = mod(self%nx, 2) == 0 .and. self%nx > 1 .and. i == self%nx/2 + 1
    end function grid_is_nyquist_x

    !> Is column j of the half-spectrum the Nyquist line kj = ny/2 (even ny > 1)?
    elemental logical function grid_is_nyquist_y(self, j) result(yes)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: j
        yes = mod(self%ny, 2) == 0 .and. self%ny > 1 .and. j == self%ny/2 + 1
    end function grid_is_nyquist_y

    !> How many full-plane modes half-spectrum row i stands for: 1 on ki = 0 and on the x Nyquist
    !> line, 2 elsewhere (the entry and its conjugate partner)
    elemental real(dp) function grid_hermitian_weight(self, i) result(w)
        class(grid_t), intent(in) :: self
        integer, intent(in) :: i
        w = 2.0_dp
        if (i == 1 .or. self%is_nyquist_x(i)) w = 1.0_dp
    end function grid_hermitian_weight

end module veslide_grid
