!> Measured topographies read from HDF5: the heights unchanged, the grid and length from the file,
!> and every refusal naming the input and the reason
module test_veslide_topography
    use, intrinsic :: ieee_arithmetic, only: ieee_value, ieee_quiet_nan
    use veslide_kinds, only: dp
    use veslide_config, only: config_t
    use veslide_hdf5, only: h5file_t
    use veslide_case, only: build_surface
    use testsuite, only: error_t, unittest_t, new_unittest, check
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
            new_unittest("height-file-not-square", test_height_not_square), &
            new_unittest("height-file-nan", test_height_nan), &
            new_unittest("height-file-without-length", test_height_length), &
            new_unittest("height-file-missing-dataset", test_height_missing) &
            ]
    end subroutine collect_topography

    !> Write a height dataset; `lx` > 0 adds the length_m attribute
    subroutine write_heights(path, h, lx, error)
        character(len=*), intent(in) :: path
        real(dp), intent(in) :: h(:, :), lx
        type(error_t), allocatable, intent(out) :: error
        type(h5file_t) :: f
        call f%open(path, 'w', error); if (allocated(error)) return
        call f%write('/height_m', h, error); if (allocated(error)) return
        if (lx > 0.0_dp) call f%writeattr('/height_m', 'length_m', lx, error)
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
        integer :: u
        h5 = unique_name(tag//'.h5')
        more = ''
        if (present(extra)) more = extra
        call write_heights(h5, h, lx, error); if (allocated(error)) return
        call read_text(tag, "&surface kind='file', file='"//h5//"' "//more//" /", cfg, error)
        if (allocated(error)) return
        call build_surface(cfg, hout, error)
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

    subroutine test_height_not_square(error)
        type(error_t), allocatable, intent(out) :: error
        real(dp) :: h(8, 6)
        h = 0
        call expect_surface_error('hsq', h, 1.0_dp, [character(len=16) :: "&surface file", "square"], error)
    end subroutine test_height_not_square

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
        call expect_surface_error('hlen', h, 0.0_dp, [character(len=16) :: "length_m", "lx_m"], error)
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

end module test_veslide_topography
