!> Measured topographies read from HDF5: the heights unchanged, the grid and length from the file,
!> and every refusal naming the input and the reason
module test_veslide_topography
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp
    use veslide_config, only: config_t
    use veslide_hdf5, only: h5file_t
    use veslide_case, only: build_surface, case_t, run_case
    use veslide_case_file, only: write_case
    use veslide_case_data, only: case_spec_t
    use veslide_case_spec, only: case_spec_of
    use testsuite, only: error_t, unittest_t, new_unittest, check
    use veslide_error, only: ERROR_INPUT
    use test_support, only: unique_name
    use test_veslide_config, only: read_text, expect_words
    implicit none
    private
    public :: collect_topography, write_heights

contains

    subroutine collect_topography(tests)
        type(unittest_t), allocatable, intent(out) :: tests(:)
        tests = [ &
            new_unittest("height-file-read", test_height_file), &
            new_unittest("height-file-rectangular", test_height_rectangular), &
            new_unittest("rectangular-file-solves-as-the-generated-surface", test_file_equals_generated), &
            new_unittest("grid-disagreeing-with-the-file-refused", test_grid_disagrees), &
            new_unittest("edge-jump-warned-once-with-its-size", test_edge_jump), &
            new_unittest("preparation-record-kept", test_preparation), &
            new_unittest("height-file-nan", test_height_nan), &
            new_unittest("height-file-without-length", test_height_length), &
            new_unittest("height-file-missing-dataset", test_height_missing), &
            new_unittest("height-file-unreadable-is-an-input-error", test_height_junk) &
            ]
    end subroutine collect_topography

    !> Write a height dataset; `lx` > 0 adds the length_m attribute (or, with `ly`, length_x_m and
    !> length_y_m), `preparation` the text attribute of that name
    subroutine write_heights(path, h, lx, error, ly, preparation)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: h(:, :), lx
        type(error_t), allocatable, intent(out) :: error
        real(dp), intent(in), optional :: ly
        character(len=*), intent(in), optional :: preparation
        type(h5file_t) :: f
        call f%open(path, 'w', error); if (allocated(error)) return
        call f%write('/height_m', h, error); if (allocated(error)) return
        if (present(ly)) then
            call f%writeattr('/height_m', 'length_x_m', lx, error); if (allocated(error)) return
            call f%writeattr('/height_m', 'length_y_m', ly, error); if (allocated(error)) return
        else if (lx > 0.0_dp) then
            call f%writeattr('/height_m', 'length_m', lx, error); if (allocated(error)) return
        end if
        if (present(preparation)) call f%writeattr('/height_m', 'preparation', preparation, error)
        call f%close()
    end subroutine write_heights

    !> Build the surface of a config naming a height file; returns the error of build_surface
    subroutine surface_from(tag, h, lx, cfg, hout, error, extra)
        character(len=*), intent(in) :: tag
        real(dp), intent(in) :: h(:, :), lx
        type(config_t), intent(out) :: cfg
        real(dp), allocatable, intent(out) :: hout(:, :)
        type(error_t), allocatable, intent(out) :: error
        character(len=*), intent(in), optional :: extra
        character(len=:), allocatable :: h5, more
        type(case_spec_t) :: spec
        integer :: u
        h5 = unique_name(tag//'.h5')
        more = ''
        if (present(extra)) more = extra
        call write_heights(h5, h, lx, error)
        if (.not. allocated(error)) call read_text(tag, "&surface kind='file', file='"//h5//"' "//more//" /", cfg, error)
        if (allocated(error)) then
            open (newunit=u, file=h5); close (u, status='delete')     ! (nothing left in the temporary directory)
            return
        end if
        call case_spec_of(cfg, spec, error)
        if (.not. allocated(error)) call build_surface(spec, hout, error)
        open (newunit=u, file=h5); close (u, status='delete')
    end subroutine surface_from

    subroutine test_height_file(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp) :: h(8, 8)
        real(dp), allocatable :: hout(:, :)
        call random_number(h)
        call surface_from('hread', h, 2.0e-3_dp, cfg, hout, error); if (allocated(error)) return
        call check(error, all(hout == h), "heights changed on the way"); if (allocated(error)) return
        call check(error, cfg%grid%nx == 8 .and. cfg%grid%ny == 8 .and. cfg%grid%lx_m == 2.0e-3_dp .and. &
                   cfg%grid%ly_m == 2.0e-3_dp, "grid from the file")
    end subroutine test_height_file

    subroutine expect_surface_error(tag, h, lx, words, error)
        character(len=*), intent(in) :: tag, words(:)
        real(dp), intent(in) :: h(:, :), lx
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp), allocatable :: hout(:, :)
        type(error_t), allocatable :: e
        call surface_from(tag, h, lx, cfg, hout, e)
        call expect_words(e, words, error)
    end subroutine expect_surface_error

    !> A rectangle (nx /= ny, lx /= ly from length_x_m, length_y_m) read as written
    subroutine test_height_rectangular(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp) :: h(8, 6)
        real(dp), allocatable :: hout(:, :)
        character(len=:), allocatable :: h5
        type(case_spec_t) :: spec
        integer :: u
        call random_number(h)
        h5 = unique_name('hrect.h5')
        call write_heights(h5, h, 2.0e-3_dp, error, ly=1.0e-3_dp); if (allocated(error)) return
        call read_text('hrect', "&surface kind='file', file='"//h5//"' /", cfg, error); if (allocated(error)) return
        call case_spec_of(cfg, spec, error)
        if (.not. allocated(error)) call build_surface(spec, hout, error)
        open (newunit=u, file=h5); close (u, status='delete')
        if (allocated(error)) return
        call check(error, all(shape(hout) == [8, 6]) .and. all(hout == h), "heights changed on the way")
        if (allocated(error)) return
        call check(error, cfg%grid%nx == 8 .and. cfg%grid%ny == 6 .and. cfg%grid%lx_m == 2.0e-3_dp .and. &
                   cfg%grid%ly_m == 1.0e-3_dp, "grid from the file")
    end subroutine test_height_rectangular

    !> A generated wave on a rectangle (64 x 32 points, 10 x 4 mm), written to a file and solved
    !> from it, gives bitwise the solve of the generated surface
    subroutine test_file_equals_generated(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: a, b
        character(len=:), allocatable :: h5
        character(len=*), parameter :: rest = " &material model = 'one_term' / &motion speed_m_s = 0.1 /"// &
            " &load mean_pressure_pa = 2e4 / &solver fft_planner = 'estimate' / &output fields = .false. /"
        integer :: u
        call read_text('gen', "&grid nx = 64, ny = 32, lx_m = 0.01, ly_m = 0.004 / &surface kind = 'cosine',"// &
                       " amplitude_m = 2e-5, wavelength_m = 0.005, direction_deg = 0 /"//rest, cfg, error)
        if (allocated(error)) return
        call run_case(cfg, a, error); if (allocated(error)) return
        h5 = unique_name('hgen.h5')
        call write_heights(h5, a%h, 0.01_dp, error, ly=0.004_dp); if (allocated(error)) return
        call read_text('fromfile', "&surface kind = 'file', file = '"//h5//"' /"//rest, cfg, error)
        if (.not. allocated(error)) call run_case(cfg, b, error)
        open (newunit=u, file=h5); close (u, status='delete')
        if (allocated(error)) return
        call check(error, all(b%state%p == a%state%p) .and. all(b%force_pa == a%force_pa), &
                   "the file's solve differs from the generated surface's")
    end subroutine test_file_equals_generated

    !> &grid may repeat the file's grid but not contradict it: refused, naming both
    subroutine test_grid_disagrees(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        real(dp) :: h(8, 8)
        real(dp), allocatable :: hout(:, :)
        call random_number(h)
        call surface_from('hsame', h, 2.0e-3_dp, cfg, hout, error, extra="/ &grid nx = 8, lx_m = 2e-3")
        if (allocated(error)) return
        call surface_from('hnx', h, 2.0e-3_dp, cfg, hout, e, extra="/ &grid nx = 16")
        call expect_words(e, [character(len=40) :: "&grid nx = 16 disagrees", "8 x 8", "--nx"], error)
        if (allocated(error)) return
        call surface_from('hlx', h, 2.0e-3_dp, cfg, hout, e, extra="/ &grid lx_m = 0.01")
        call expect_words(e, [character(len=40) :: "&grid lx_m = ", "disagrees"], error)
    end subroutine test_grid_disagrees

    !> A cropped, non-periodic scan (a ramp along x: its edges jump by sqrt(12) h_rms) gets one
    !> warning with the number; a periodic wave none
    subroutine test_edge_jump(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp) :: h(32, 16)
        real(dp), allocatable :: hout(:, :)
        integer :: i, j
        do j = 1, 16
            do i = 1, 32
                h(i, j) = real(i, dp)*1.0e-6_dp
            end do
        end do
        call surface_from('hramp', h, 2.0e-3_dp, cfg, hout, error); if (allocated(error)) return
        call check(error, size(cfg%warnings) == 1, "one warning for the ramp"); if (allocated(error)) return
        call check(error, index(cfg%warnings(1)%text, "jump by 3.36 h_rms") > 0 .and. &
                   index(cfg%warnings(1)%text, "along x") > 0, cfg%warnings(1)%text)
        if (allocated(error)) return
        do j = 1, 16
            do i = 1, 32
                h(i, j) = cos(6.283185307179586_dp*(i - 1)/32)*1.0e-6_dp
            end do
        end do
        call surface_from('hwave', h, 2.0e-3_dp, cfg, hout, error); if (allocated(error)) return
        call check(error, size(cfg%warnings) == 0, "a periodic wave warned"); if (allocated(error)) return
        ! a ramp along y over 150 rows (three blocks of rows read): the jump along y, none along x
        call ramp_y(error)
    contains
        subroutine ramp_y(error)
            type(error_t), allocatable, intent(out) :: error
            real(dp) :: hy(8, 150)
            real(dp), allocatable :: hy_out(:, :)
            character(len=16) :: expected
            do j = 1, 150
                hy(:, j) = 1.0_dp + real(j, dp)*1.0e-6_dp      ! far from zero: moments about a height
            end do
            call surface_from('hrampy', hy, 2.0e-3_dp, cfg, hy_out, error); if (allocated(error)) return
            ! jump 149 steps over an rms of sqrt((150^2 - 1)/12) steps
            write (expected, '(f0.2)') 149.0_dp/sqrt((150.0_dp**2 - 1.0_dp)/12.0_dp)
            call check(error, size(cfg%warnings) == 1, "one warning for the ramp along y"); if (allocated(error)) return
            call check(error, index(cfg%warnings(1)%text, "jump by "//trim(expected)//" h_rms") > 0 .and. &
                       index(cfg%warnings(1)%text, "along y") > 0, cfg%warnings(1)%text)
        end subroutine ramp_y
    end subroutine test_edge_jump

    !> The file's record of its preparation is kept, and written to the output
    subroutine test_preparation(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(case_t) :: c
        type(h5file_t) :: f
        real(dp) :: h(8, 8)
        character(len=:), allocatable :: h5, out, text
        integer :: u
        call random_number(h)
        h = 1.0e-6_dp*h                  ! (1 um over cells of 0.25 mm: an rms slope of 0.005)
        h5 = unique_name('hprep.h5')
        call write_heights(h5, h, 2.0e-3_dp, error, preparation='{"detrend": "plane"}'); if (allocated(error)) return
        out = unique_name('hprep-out.h5')
        call read_text('hprep', "&surface kind='file', file='"//h5//"' / &solver fft_planner = 'estimate' /", cfg, error)
        if (.not. allocated(error)) call run_case(cfg, c, error)
        if (.not. allocated(error)) call write_case(out, c, error)
        open (newunit=u, file=h5); close (u, status='delete')
        if (allocated(error)) return
        call check(error, cfg%surface%preparation == '{"detrend": "plane"}', "preparation: "//cfg%surface%preparation)
        if (allocated(error)) return
        call f%open(out, 'r', error); if (allocated(error)) return
        call f%read_text('/input/surface_preparation', text, error); if (allocated(error)) return
        call f%close()
        open (newunit=u, file=out); close (u, status='delete')
        call check(error, text == '{"detrend": "plane"}', "the output's /input/surface_preparation: "//text)
    end subroutine test_preparation

    subroutine test_height_nan(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(8, 8)
        h = 0; h(3, 4) = ieee_value(1.0_dp, ieee_quiet_nan)
        call expect_surface_error('hnan', h, 1.0_dp, [character(len=16) :: "&surface file", "NaN"], error)
    end subroutine test_height_nan

    subroutine test_height_length(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(8, 8)
        h = 0
        call expect_surface_error('hlen', h, 0.0_dp, [character(len=16) :: "length_x_m", "lx_m"], error)
    end subroutine test_height_length

    subroutine test_height_missing(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        real(dp), allocatable :: hout(:, :)
        type(error_t), allocatable :: e
        real(dp) :: h(4, 4)
        h = 0
        call surface_from('hmiss', h, 1.0_dp, cfg, hout, e, extra="dataset='/topo'")
        call expect_words(e, [character(len=16) :: "&surface file", "/topo"], error)
    end subroutine test_height_missing

    !> A file that is not HDF5 is the input's fault (exit status 1), not a failed I/O (3, which a
    !> batch script may retry): the HDF5 library's error is replaced by the input's
    subroutine test_height_junk(error)
        type(error_t), allocatable, intent(out) :: error
        type(config_t) :: cfg
        type(error_t), allocatable :: e
        character(len=:), allocatable :: junk
        integer :: u
        junk = unique_name('junk.h5')
        open (newunit=u, file=junk, status='replace'); write (u, '(a)') 'not an HDF5 file'; close (u)
        call read_text('hjunk', "&surface kind='file', file='"//junk//"' /", cfg, e)
        open (newunit=u, file=junk); close (u, status='delete')
        call check(error, allocated(e), "a junk height file was read"); if (allocated(error)) return
        call check(error, index(e%message, "not a readable HDF5 file") > 0 .and. e%category == ERROR_INPUT, &
                   "a junk height file: "//e%message)
    end subroutine test_height_junk

end module test_veslide_topography
